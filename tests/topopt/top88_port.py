"""A line-by-line port of top88.m (Andreassen, Clausen, Schevenels, Lazarov, Sigmund 2011,
"Efficient topology optimization in MATLAB using 88 lines of code", Struct Multidisc Optim
43:1-16, doi:10.1007/s00158-010-0594-7): the independent reference of the package's MBB
results. MATLAB's 1-based indices become 0-based; K \\ F becomes SciPy's spsolve. It is not
a call into flexfem.topopt, on purpose."""
import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.linalg import spsolve


def lk(nu):
    """top88's element stiffness of a unit square, E = 1."""
    A11 = np.array([[12, 3, -6, -3], [3, 12, 3, 0], [-6, 3, 12, -3], [-3, 0, -3, 12]])
    A12 = np.array([[-6, -3, 0, 3], [-3, -6, -3, -6], [0, -3, -6, 3], [3, -6, 3, -6]])
    B11 = np.array([[-4, 3, -2, 9], [3, -4, -9, 4], [-2, -9, -4, -3], [9, 4, -3, -4]])
    B12 = np.array([[2, -3, 4, -9], [-3, 2, 9, -2], [4, 9, 2, 3], [-9, -2, 3, 2]])
    KE = 1 / (1 - nu**2) / 24 * (np.block([[A11, A12], [A12.T, A11]])
                                 + nu * np.block([[B11, B12], [B12.T, B11]]))
    return KE


def prepare_filter(nelx, nely, rmin):
    """top88's filter matrix H and its row sums Hs."""
    iH = np.ones(nelx * nely * (2 * (int(np.ceil(rmin)) - 1) + 1) ** 2, dtype=int)
    jH = np.ones(iH.shape, dtype=int)
    sH = np.zeros(iH.shape)
    k = 0
    for i1 in range(1, nelx + 1):
        for j1 in range(1, nely + 1):
            e1 = (i1 - 1) * nely + j1
            for i2 in range(max(i1 - (int(np.ceil(rmin)) - 1), 1),
                            min(i1 + (int(np.ceil(rmin)) - 1), nelx) + 1):
                for j2 in range(max(j1 - (int(np.ceil(rmin)) - 1), 1),
                                min(j1 + (int(np.ceil(rmin)) - 1), nely) + 1):
                    e2 = (i2 - 1) * nely + j2
                    iH[k] = e1
                    jH[k] = e2
                    sH[k] = max(0, rmin - np.sqrt((i1 - i2) ** 2 + (j1 - j2) ** 2))
                    k = k + 1
    H = coo_matrix((sH[:k], (iH[:k] - 1, jH[:k] - 1)), shape=(nelx * nely, nelx * nely)).tocsr()
    Hs = np.asarray(H.sum(axis=1)).ravel()
    return H, Hs


def top88(nelx, nely, volfrac, penal, rmin, ft, max_loop=None):
    """Returns (c, loop, xPhys) of the MBB half-beam; ft = 1 sensitivity, 2 density filter."""
    # MATERIAL PROPERTIES
    E0 = 1.0
    Emin = 1e-9
    nu = 0.3
    # PREPARE FINITE ELEMENT ANALYSIS
    KE = lk(nu)
    nodenrs = np.arange(1, (1 + nelx) * (1 + nely) + 1).reshape(1 + nelx, 1 + nely).T
    edofVec = (2 * nodenrs[:-1, :-1] + 1).reshape(nelx * nely, order="F")
    edofMat = (np.tile(edofVec[:, None], (1, 8))
               + np.array([0, 1, 2 * nely + 2, 2 * nely + 3, 2 * nely, 2 * nely + 1, -2, -1]))
    edofMat = edofMat - 1  # 0-based
    iK = np.kron(edofMat, np.ones((8, 1), dtype=int)).T.reshape(-1, order="F")
    jK = np.kron(edofMat, np.ones((1, 8), dtype=int)).T.reshape(-1, order="F")
    # DEFINE LOADS AND SUPPORTS (HALF MBB-BEAM)
    ndof = 2 * (nely + 1) * (nelx + 1)
    F = np.zeros(ndof)
    F[1] = -1
    U = np.zeros(ndof)
    fixeddofs = np.union1d(np.arange(0, 2 * (nely + 1), 2), [2 * (nelx + 1) * (nely + 1) - 1])
    alldofs = np.arange(ndof)
    freedofs = np.setdiff1d(alldofs, fixeddofs)
    # PREPARE FILTER
    H, Hs = prepare_filter(nelx, nely, rmin)
    # INITIALIZE ITERATION
    x = np.full((nely, nelx), volfrac)
    xPhys = x.copy()
    loop = 0
    change = 1.0
    c = np.nan
    # START ITERATION
    while change > 0.01 and (max_loop is None or loop < max_loop):
        loop = loop + 1
        # FE-ANALYSIS
        sK = (KE.reshape(64, 1, order="F") * (Emin + xPhys.reshape(-1, order="F") ** penal
                                               * (E0 - Emin))).reshape(-1, order="F")
        K = coo_matrix((sK, (iK, jK)), shape=(ndof, ndof)).tocsc()
        K = (K + K.T) / 2
        U[freedofs] = spsolve(K[freedofs, :][:, freedofs], F[freedofs])
        # OBJECTIVE FUNCTION AND SENSITIVITY ANALYSIS
        Ue = U[edofMat]
        ce = np.sum((Ue @ KE) * Ue, axis=1).reshape(nely, nelx, order="F")
        c = np.sum((Emin + xPhys**penal * (E0 - Emin)) * ce)
        dc = -penal * (E0 - Emin) * xPhys ** (penal - 1) * ce
        dv = np.ones((nely, nelx))
        # FILTERING/MODIFICATION OF SENSITIVITIES
        if ft == 1:
            xf, dcf = x.reshape(-1, order="F"), dc.reshape(-1, order="F")
            dc = (H @ (xf * dcf) / Hs / np.maximum(1e-3, xf)).reshape(nely, nelx, order="F")
        elif ft == 2:
            dc = (H @ (dc.reshape(-1, order="F") / Hs)).reshape(nely, nelx, order="F")
            dv = (H @ (dv.reshape(-1, order="F") / Hs)).reshape(nely, nelx, order="F")
        # OPTIMALITY CRITERIA UPDATE OF DESIGN VARIABLES AND PHYSICAL DENSITIES
        l1 = 0.0
        l2 = 1e9
        move = 0.2
        while (l2 - l1) / (l1 + l2) > 1e-3:
            lmid = 0.5 * (l2 + l1)
            xnew = np.maximum(0, np.maximum(x - move, np.minimum(1, np.minimum(
                x + move, x * np.sqrt(-dc / dv / lmid)))))
            if ft == 1:
                xPhys = xnew
            elif ft == 2:
                xPhys = (H @ xnew.reshape(-1, order="F") / Hs).reshape(nely, nelx, order="F")
            if np.sum(xPhys) > volfrac * nelx * nely:
                l1 = lmid
            else:
                l2 = lmid
        change = np.max(np.abs(xnew - x))
        x = xnew
    return c, loop, xPhys
