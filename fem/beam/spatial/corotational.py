"""The spatial co-rotational beam element of Battini & Pacoste (2002), vectorised.

Battini J.-M., Pacoste C., "Co-rotational beam elements with warping effects in
instability problems", Computer Methods in Applied Mechanics and Engineering 191 (2002)
1755-1789 (their element without warping): the element's rigid frame R_r follows its chord and
the mean of the two nodal triads; the local deformations are the extension and the rotation
vectors of the nodal triads relative to R_r, fed to the linear element (element.py). Nodal
rotations are rotation matrices updated multiplicatively with spatial spins, and the
internal force and consistent tangent below are with respect to those spins (the tangent
is not symmetric away from equilibrium). The frame is undefined where the mean nodal y
axis turns onto the chord: a 90-degree rotation within one element, never reached by a
mesh that resolves the deformation.
"""
import numpy as np

from .rotations import logm, skew, ts_inv, ts_inv_tangent


def _frame(x1, x2, R1, R2, R0):
    """Chord length l_n, unit chord r1 and rigid frame R_r (columns r1, r2, r3); the
    nodal auxiliary vectors q_1, q_2 = R_i R0 e_2 (n_e, 3)."""
    d = x2 - x1
    ln = np.linalg.norm(d, axis=1)
    r1 = d / ln[:, None]
    q1 = np.einsum("eij,ej->ei", R1, R0[:, :, 1])
    q2 = np.einsum("eij,ej->ei", R2, R0[:, :, 1])
    r3 = np.cross(r1, 0.5 * (q1 + q2))
    r3 /= np.linalg.norm(r3, axis=1)[:, None]
    r2 = np.cross(r3, r1)
    return ln, r1, np.stack([r1, r2, r3], axis=2), q1, q2


def _g_transpose(Rr, q1, q2, ln):
    """(n_e, 3, 12) G^T: the local spin of R_r per global nodal variation (local
    components), as Battini & Pacoste derive it; eta = q_x / q_y and the local components of
    q_1, q_2."""
    ql1 = np.einsum("eji,ej->ei", Rr, q1)
    ql2 = np.einsum("eji,ej->ei", Rr, q2)
    ql = 0.5 * (ql1 + ql2)
    eta = ql[:, 0] / ql[:, 1]
    e11, e12 = ql1[:, 0] / ql[:, 1], ql1[:, 1] / ql[:, 1]
    e21, e22 = ql2[:, 0] / ql[:, 1], ql2[:, 1] / ql[:, 1]
    G = np.zeros((len(ln), 3, 12))
    G[:, 0, 2], G[:, 0, 8] = eta / ln, -eta / ln
    G[:, 0, 3], G[:, 0, 4] = e12 / 2.0, -e11 / 2.0
    G[:, 0, 9], G[:, 0, 10] = e22 / 2.0, -e21 / 2.0
    G[:, 1, 2], G[:, 1, 8] = 1.0 / ln, -1.0 / ln
    G[:, 2, 1], G[:, 2, 7] = -1.0 / ln, 1.0 / ln
    return G, eta, (ql1, ql2)


def local_deformations(model, x, R):
    """Natural deformations p_l (n_e, 7): extension (m) and the two ends' rotation vectors
    relative to the rigid frame (rad), at positions x (n, 3) and nodal rotations R (n, 3,
    3) (rotations from the reference configuration); with the frame quantities."""
    e = model.elements
    R0 = model.frames
    x1, x2 = x[e[:, 0]], x[e[:, 1]]
    ln, r1, Rr, q1, q2 = _frame(x1, x2, R[e[:, 0]], R[e[:, 1]], R0)
    D = model.nodes[e[:, 1]] - model.nodes[e[:, 0]]
    du = (x2 - x1) - D
    L0 = model.lengths
    stretch = (2.0 * np.einsum("ei,ei->e", D, du) + np.einsum("ei,ei->e", du, du)) / (ln + L0)
    RrT = Rr.transpose(0, 2, 1)
    th1 = logm(RrT @ R[e[:, 0]] @ R0)
    th2 = logm(RrT @ R[e[:, 1]] @ R0)
    pl = np.column_stack([stretch, th1, th2])
    return pl, (ln, r1, Rr, q1, q2)


def kinematics(model, x, R):
    """Natural deformations p_l (n_e, 7), B_a (n_e, 7, 7) with d p_l = B_a d p_a, and
    B_g (n_e, 7, 12) with d p_a = B_g (du_1, dw_1, du_2, dw_2) (global components,
    spins dw); the frame quantities for the tangent in ``extra``."""
    pl, (ln, r1, Rr, q1, q2) = local_deformations(model, x, R)
    n = len(ln)
    Ba = np.zeros((n, 7, 7))
    Ba[:, 0, 0] = 1.0
    Ba[:, 1:4, 1:4] = ts_inv(pl[:, 1:4])
    Ba[:, 4:7, 4:7] = ts_inv(pl[:, 4:7])
    Gt, eta, qloc = _g_transpose(Rr, q1, q2, ln)
    P = -np.concatenate([Gt, Gt], axis=1)
    P[:, 0:3, 3:6] += np.eye(3)
    P[:, 3:6, 9:12] += np.eye(3)
    E = np.zeros((n, 12, 12))
    for k in range(4):
        E[:, 3 * k:3 * k + 3, 3 * k:3 * k + 3] = Rr
    r = np.zeros((n, 12))
    r[:, 0:3], r[:, 6:9] = -r1, r1
    Bg = np.concatenate([r[:, None, :], np.einsum("eij,ekj->eik", P, E)], axis=1)
    return pl, Ba, Bg, (ln, r1, r, P, E, Gt, eta, qloc)


def internal_forces(model, Kl, x, R, tangent=True):
    """Global element forces f (n_e, 12) conjugate to (du_1, dw_1, du_2, dw_2) (spins
    dw), the consistent tangent K (n_e, 12, 12) (None if not ``tangent``) and the local
    forces f_l (n_e, 7): N (N, tension > 0) and the end moments (N m, local axes) acting
    on the element. Kl: (n_e, 7, 7) basic stiffness."""
    pl, Ba, Bg, (ln, r1, r, P, E, Gt, eta, qloc) = kinematics(model, x, R)
    fl = np.einsum("eij,ej->ei", Kl, pl)
    fa = np.einsum("eji,ej->ei", Ba, fl)
    f = np.einsum("eji,ej->ei", Bg, fa)
    if not tangent:
        return f, None, fl
    Ka = np.einsum("eki,ekl,elj->eij", Ba, Kl, Ba)
    Ka[:, 1:4, 1:4] += ts_inv_tangent(pl[:, 1:4], fl[:, 1:4])
    Ka[:, 4:7, 4:7] += ts_inv_tangent(pl[:, 4:7], fl[:, 4:7])
    K = np.einsum("eki,ekl,elj->eij", Bg, Ka, Bg)
    K += _geometric(fa, r1, ln, r, P, E, Gt, eta)
    K -= _eta_term(fa, ln, P, E, qloc)
    return f, K, fl


def _geometric(fa, r1, ln, r, P, E, Gt, eta):
    """K_m = D N - E Q G^T E^T + E G a r: the variation of B_g^T at fixed f_a."""
    n = len(ln)
    D3 = (np.eye(3) - np.einsum("ei,ej->eij", r1, r1)) / ln[:, None, None]
    K = np.zeros((n, 12, 12))
    for i, si in ((0, 1.0), (6, -1.0)):
        for j, sj in ((0, 1.0), (6, -1.0)):
            K[:, i:i + 3, j:j + 3] += si * sj * fa[:, 0, None, None] * D3
    pm = np.einsum("eji,ej->ei", P, fa[:, 1:7])  # P^T m (n_e, 12), local
    Q = skew(pm.reshape(n, 4, 3)).reshape(n, 12, 3)
    EQ = np.einsum("eij,ejk->eik", E, Q)
    K -= np.einsum("eik,ekj,elj->eil", EQ, Gt, E)
    ms = fa[:, 1:4] + fa[:, 4:7]
    a = np.column_stack([np.zeros(n), (eta * ms[:, 0] + ms[:, 1]) / ln, ms[:, 2] / ln])
    Ga = np.einsum("eki,ek->ei", Gt, a)
    K += np.einsum("ei,ej->eij", np.einsum("eij,ej->ei", E, Ga), r)
    return K


def _eta_term(fa, ln, P, E, qloc):
    """E (dG/dp) m_s: the variation of G through eta, eta_ij under the local moments'
    sum m_s = m_1 + m_2 (Battini & Pacoste neglect it; kept so that the tangent is the
    exact derivative). The local auxiliary vectors vary as dq_il = -S(q_il) dw_i, dw_i
    the local deformational spins P E^T dp."""
    ql1, ql2 = qloc
    W = np.einsum("eij,ekj->eik", P, E)  # (n_e, 6, 12)
    dq1 = -np.einsum("eij,ejk->eik", skew(ql1), W[:, 0:3])
    dq2 = -np.einsum("eij,ejk->eik", skew(ql2), W[:, 3:6])
    qy = 0.5 * (ql1[:, 1] + ql2[:, 1])
    dqy = 0.5 * (dq1[:, 1] + dq2[:, 1])
    ratio = lambda num, dnum: (dnum - (num / qy)[:, None] * dqy) / qy[:, None]
    d_eta = ratio(0.5 * (ql1[:, 0] + ql2[:, 0]), 0.5 * (dq1[:, 0] + dq2[:, 0]))
    c = np.zeros((len(ln), 12, 12))
    c[:, 2], c[:, 8] = d_eta / ln[:, None], -d_eta / ln[:, None]
    c[:, 3], c[:, 4] = ratio(ql1[:, 1], dq1[:, 1]) / 2.0, -ratio(ql1[:, 0], dq1[:, 0]) / 2.0
    c[:, 9], c[:, 10] = ratio(ql2[:, 1], dq2[:, 1]) / 2.0, -ratio(ql2[:, 0], dq2[:, 0]) / 2.0
    ms0 = fa[:, 1] + fa[:, 4]
    return ms0[:, None, None] * np.einsum("eij,ejk->eik", E, c)
