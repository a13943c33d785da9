"""Independent reference solutions for the beam-model tests (scipy ODE / root solves)."""
from functools import lru_cache

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq


def elastica_tip(k: float):
    """Cantilever elastica under a dead tip load P perpendicular to the undeformed axis,
    k = P L^2 / EI: (shortening u/L, deflection v/L, tip rotation rad), by shooting on
    theta'' = -k cos(theta) over s in [0, 1] with theta(0) = 0, theta'(1) = 0."""
    def end(curvature0):
        rhs = lambda s, y: [y[1], -k * np.cos(y[0]), np.cos(y[0]), np.sin(y[0])]
        return solve_ivp(rhs, [0.0, 1.0], [0.0, curvature0, 0.0, 0.0], rtol=1e-12,
                         atol=1e-14).y[:, -1]
    c0 = brentq(lambda c: end(c)[1], 0.0, k, xtol=1e-14)
    theta, _, x, y = end(c0)
    return 1.0 - x, y, theta


@lru_cache(maxsize=None)
def timoshenko_cantilever_hz(E, nu, rho, A, I, L, n, kappa=5.0 / 6.0):
    """The n lowest natural frequencies (Hz) of a clamped-free Timoshenko beam: roots of the
    2x2 determinant of the free-end conditions (M = 0, V = 0) propagated from the clamped
    end with the exact transfer matrix exp(A(omega) L) of the equations
    kGA (w'' - psi') + rho A w2 w = 0, EI psi'' + kGA (w' - psi) + rho I w2 psi = 0."""
    G = E / (2 * (1 + nu))
    kGA = kappa * G * A

    def det(omega):
        w2 = omega**2
        Amat = np.array([[0, 1, 0, 0],
                         [-rho * A * w2 / kGA, 0, 0, 1],
                         [0, 0, 0, 1],
                         [0, -kGA / (E * I), kGA / (E * I) - rho * I * w2 / (E * I), 0]])
        lam, V = np.linalg.eig(Amat * L)   # distinct eigenvalues: expm = V e^lam V^-1
        P = np.real(V @ np.diag(np.exp(lam)) @ np.linalg.inv(V))
        cols = P[:, [1, 3]]              # y(0) = (0, a, 0, b)
        bc = np.array([cols[3], cols[1] - cols[2]])  # psi'(L) = 0, w'(L) - psi(L) = 0
        return np.linalg.det(bc)

    # scan in omega (rad/s) from the Euler-Bernoulli first frequency down-scaled
    w1 = 1.8751**2 * np.sqrt(E * I / (rho * A * L**4))
    grid = np.linspace(0.05 * w1, 25 * w1, 600)
    vals = np.array([det(w) for w in grid])
    roots = []
    for a, b, fa, fb in zip(grid[:-1], grid[1:], vals[:-1], vals[1:]):
        if np.sign(fa) != np.sign(fb):
            roots.append(brentq(det, a, b, xtol=1e-12 * b))
        if len(roots) == n:
            break
    return tuple(np.array(roots) / (2 * np.pi))
