"""The force inverter written the way the educational codes write it: top88's loop
(Andreassen et al. 2011, its arrays and assembly, SciPy's spsolve for K \\ F) with the input
and output springs and two right-hand sides of Sigmund's mechanism example, and Svanberg's
MMA called as the educational MMA codes call ``mmasub`` (mmapy, default settings). The
independent reference of the benchmark's inverter row: it is not a call into
flexfem.topopt. The problem is the benchmark's (the upper half, its symmetry line at the
bottom, the top five elements of the left edge clamped), numbered as top88 numbers nodes
(column by column from the top left)."""
import numpy as np
from mmapy import mmasub
from scipy.sparse import coo_matrix
from scipy.sparse.linalg import spsolve
from top88_port import lk, prepare_filter


def inverter88(nelx, nely, volfrac, penal, rmin, max_loop, k_spring=0.1, clamp=5):
    """Returns (u_out of the last analysed design, loop, xPhys); density filter, MMA with
    move 0.2, the objective scaled by its first largest gradient, the volume by its bound."""
    E0, Emin, nu = 1.0, 1e-9, 0.3
    KE = lk(nu)
    nodenrs = np.arange(1, (1 + nelx) * (1 + nely) + 1).reshape(1 + nelx, 1 + nely).T
    edofVec = (2 * nodenrs[:-1, :-1] + 1).reshape(nelx * nely, order="F")
    edofMat = (np.tile(edofVec[:, None], (1, 8))
               + np.array([0, 1, 2 * nely + 2, 2 * nely + 3, 2 * nely, 2 * nely + 1, -2, -1])) - 1
    iK = np.kron(edofMat, np.ones((8, 1), dtype=int)).T.reshape(-1, order="F")
    jK = np.kron(edofMat, np.ones((1, 8), dtype=int)).T.reshape(-1, order="F")
    ndof = 2 * (nely + 1) * (nelx + 1)
    din, dout = 2 * nely, 2 * (nelx * (nely + 1) + nely)
    F = np.zeros((ndof, 2))
    F[din, 0], F[dout, 1] = 1.0, 1.0
    U = np.zeros((ndof, 2))
    bottom = np.arange(nelx + 1) * (nely + 1) + nely
    fixeddofs = np.union1d(2 * bottom + 1, np.arange(0, 2 * (clamp + 1)))
    freedofs = np.setdiff1d(np.arange(ndof), fixeddofs)
    springs = coo_matrix(([k_spring, k_spring], ([din, dout], [din, dout])), shape=(ndof, ndof))
    H, Hs = prepare_filter(nelx, nely, rmin)
    n = nelx * nely
    x = np.full(n, volfrac)
    xPhys = x.copy()
    xold1, xold2 = x[:, None].copy(), x[:, None].copy()
    low, upp = np.zeros((n, 1)), np.ones((n, 1))
    loop, change, scale, c = 0, 1.0, None, np.nan
    while change > 0.01 and loop < max_loop:
        loop += 1
        sK = (KE.reshape(64, 1, order="F") * (Emin + xPhys ** penal * (E0 - Emin))).reshape(
            -1, order="F")
        K = (coo_matrix((sK, (iK, jK)), shape=(ndof, ndof)) + springs).tocsc()
        K = (K + K.T) / 2
        U[freedofs] = spsolve(K[freedofs, :][:, freedofs], F[freedofs])
        c = U[dout, 0]
        ce = np.sum((U[edofMat, 1] @ KE) * U[edofMat, 0], axis=1)
        dc = -penal * (E0 - Emin) * xPhys ** (penal - 1) * ce
        dc = H @ (dc / Hs)
        dv = H @ (np.ones(n) / Hs) / n
        scale = scale or float(np.max(np.abs(dc)))
        xmma, *_, low, upp = mmasub(
            1, n, loop, x[:, None], np.zeros((n, 1)), np.ones((n, 1)), xold1, xold2,
            c / scale, (dc / scale)[:, None], np.array([[xPhys.mean() / volfrac - 1]]),
            (dv / volfrac)[None, :], low, upp, 1.0, np.zeros((1, 1)), np.full((1, 1), 1000.0),
            np.ones((1, 1)), move=0.2)
        xold2, xold1 = xold1, x[:, None].copy()
        xnew = xmma.ravel()
        xPhys = H @ xnew / Hs
        change = np.max(np.abs(xnew - x))
        x = xnew
    return c, loop, xPhys
