"""A rigid face's compliance as a result (:class:`Compliance`), and moving it to another
point and axes; numpy only, so that the beam model's face gives it without the continuum's
assembly (the continuum's :func:`~flexfem.fem.compliance.compliance_matrix` computes it)."""
from dataclasses import dataclass
import math

import numpy as np


@dataclass(frozen=True, eq=False)
class Compliance:
    """The compliance of a rigid face (:func:`flexfem.fem.compliance_matrix`).

    Attributes
    ----------
    face : str
        The group.
    matrix : ndarray
        The compliance (m/N, 1/N, rad/(N m)) of the face's (translations, rotations) under
        (forces, moments) at ``point``: 3 x 3 in 2-D (x, y, theta_z), 6 x 6 in 3-D (x, y, z,
        theta_x, theta_y, theta_z), in the axes ``frame``.
    point : ndarray
        The reference point (m, current coordinates).
    frame : ndarray
        (dim, dim) the axes of ``matrix``: columns are the axes' global components.
    """

    face: str
    matrix: np.ndarray
    point: np.ndarray
    frame: np.ndarray

    @property
    def dim(self) -> int:
        return len(self.point)

    @property
    def angle(self) -> float:
        """2-D: rotation (rad) of the frame from the global axes."""
        return float(math.atan2(self.frame[1, 0], self.frame[0, 0]))

    @property
    def stiffness(self) -> np.ndarray:
        """Stiffness matrix (N/m, N, N m/rad): the inverse of ``matrix``."""
        return np.linalg.inv(self.matrix)

    def principal(self) -> tuple[np.ndarray, np.ndarray]:
        """(compliances (dim,) m/N ascending, directions (dim, dim) as columns, frame
        components) of the translational block: forces that translate the point along
        themselves; of its symmetric part where a dead moment's load stiffness (3-D, about a
        nonlinear state) makes it non-symmetric."""
        n = self.dim
        block = self.matrix[:n, :n]
        return np.linalg.eigh(0.5 * (block + block.T))

    @property
    def centre_of_compliance(self) -> np.ndarray:
        """Global coordinates (m) of the point about which a force causes no rotation (the
        elastic centre); in 3-D the point of least force-rotation coupling (Frobenius norm),
        which decouples exactly where such a point exists."""
        C, n = self.matrix, self.dim
        if n == 2:
            local = np.array([-C[2, 1] / C[2, 2], C[2, 0] / C[2, 2]])
        else:
            # rotation per force about P + d: C_rt + C_rr [d]x, linear in d
            basis = [skew(e) for e in np.eye(3)]
            A = np.column_stack([(C[3:, 3:] @ S).ravel() for S in basis])
            local = np.linalg.lstsq(A, -C[3:, :3].ravel(), rcond=None)[0]
        return self.point + self.frame @ local

    def _response(self, direction) -> tuple:
        """(unit direction, response (translations, rotations) to a unit force along it)."""
        d = np.asarray(direction, dtype=float)
        if d.shape != (self.dim,) or not np.all(np.isfinite(d)) or not np.linalg.norm(d) > 0:
            raise ValueError(f"direction = {direction!r} must be {self.dim} finite numbers, "
                             "not all 0")
        d = d / np.linalg.norm(d)
        return d, self.matrix[:, :self.dim] @ d

    def support_stiffness(self, direction) -> tuple[float, float]:
        """(motion stiffness (N/m), support stiffness (N/m)) for motion along ``direction``
        (frame components): the motion stiffness with every other coordinate free, the
        support stiffness across the motion with the motion held and the rotations free (in
        3-D the weakest direction across)."""
        d, response = self._response(direction)
        n = self.dim
        across = np.linalg.svd(d[None, :])[2][1:]  # orthonormal complement, (n - 1, n)
        Q = np.zeros((len(self.matrix), len(self.matrix)))
        Q[0, :n], Q[1:n, :n], Q[n:, n:] = d, across, np.eye(len(self.matrix) - n)
        K = np.linalg.inv(Q @ self.matrix @ Q.T)
        held = np.linalg.inv(K[1:, 1:])[:n - 1, :n - 1]
        return 1.0 / float(d @ response[:n]), 1.0 / float(np.linalg.eigvalsh(held).max())

    def support_stiffness_ratio(self, direction) -> float:
        """Support stiffness over motion stiffness (-) for motion along ``direction``."""
        motion, support = self.support_stiffness(direction)
        return support / motion

    def parasitic(self, direction) -> tuple:
        """(motion across (m/m), rotation (rad/m)) per unit motion along ``direction`` when
        the point is pushed along it. 2-D: numbers, 'across' being ``direction`` turned by
        +90 degrees; 3-D: the across-translation and rotation vectors (frame components)."""
        d, response = self._response(direction)
        n = self.dim
        along = float(d @ response[:n])
        if n == 2:
            return float(np.array([-d[1], d[0]]) @ response[:2]) / along, response[2] / along
        return (response[:3] - along * d) / along, response[3:] / along


def skew(v) -> np.ndarray:
    return np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])


def _rotation(angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s], [s, c]])


def rotation_frame(dim, angle, frame) -> np.ndarray:
    """(dim, dim) orthonormal axes (columns) from ``angle`` (2-D, rad) or ``frame``."""
    if not (isinstance(angle, (int, float)) and math.isfinite(angle)):
        raise ValueError(f"angle = {angle!r} must be a finite number (rad)")
    if frame is None:
        if dim == 3 and angle != 0:
            raise ValueError(f"angle = {angle!r} is for 2-D models; give frame in 3-D")
        return _rotation(angle) if dim == 2 else np.eye(3)
    R = np.asarray(frame, dtype=float)
    if angle != 0 or R.shape != (dim, dim) or not np.allclose(R.T @ R, np.eye(dim), atol=1e-9):
        raise ValueError(f"frame = {frame!r} must be an orthonormal {dim} x {dim} matrix "
                         "(columns: the axes), given instead of angle")
    return R


def moved_compliance(face: str, C: np.ndarray, centre, point, R: np.ndarray) -> Compliance:
    """The Compliance of ``face`` from ``C`` (about ``centre``, global axes) moved to
    ``point`` (m; None: the centre) and turned into the axes ``R`` (columns)."""
    dim = len(centre)
    P = np.asarray(centre, dtype=float) if point is None else np.asarray(point, dtype=float)
    if P.shape != (dim,) or not np.all(np.isfinite(P)):
        raise ValueError(f"point = {point!r} must be {dim} finite coordinates (m)")
    d = P - centre
    n = len(C)
    # u_P = u_c + theta x d: translations gain -[d]x theta (2-D: theta (-d_y, d_x))
    A = np.eye(n)
    if dim == 2:
        A[0, 2], A[1, 2] = -d[1], d[0]
    else:
        A[:3, 3:] = -skew(d)
    Rn = np.zeros((n, n))
    Rn[:dim, :dim] = R.T
    Rn[dim:, dim:] = R.T if dim == 3 else 1.0
    return Compliance(face, Rn @ A @ C @ A.T @ Rn.T, P, R)
