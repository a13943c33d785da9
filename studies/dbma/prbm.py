"""The DBMA paper's pseudo-rigid-body model, evaluated exactly as printed.

Source: Micromachines 2020, 11(3), 312, Sections 2-3 (Eqs. 6-8, 11, 14, 15, 19, 20). One
function per equation; all inputs and outputs in SI units (m, Pa, kg, N/m, Hz). The formulas
are not corrected where they disagree with the paper's own numbers: the disagreements are
reported in docs/dbma-analytical.md.
"""
import math

import numpy as np

from ...geometry.dbma.params import DBMAParams


def hinge_second_moment(p: DBMAParams) -> float:
    """Second moment of area of the flexure hinge, Iz = d b^3 / 12 (m^4) (text below Eq. 6)."""
    return p.d * p.b**3 / 12.0


def hinge_stiffness_matrix(p: DBMAParams) -> np.ndarray:
    """Stiffness coefficient matrix of the hinges at both ends of an arm (Eq. 6).

    K = diag(12 E Iz / l^3, 2 (2 l + e) E Iz / l^2): the first entry in N/m (translation
    omega = 1), the second in N m/rad (rotation theta = 1), as printed.
    """
    EI = p.E * hinge_second_moment(p)
    return np.diag([12.0 * EI / p.l**3, 2.0 * (2.0 * p.l + p.e) * EI / p.l**2])


def amplification_ratio(p: DBMAParams) -> float:
    """Displacement amplification ratio R = 4 dy/dx of the DBMA (Eq. 7), dimensionless.

    R = 4 l (3 h^2 + 8 l^2 + 4 e l) / (4 b^2 e + 8 b^2 l + 3 e h l).
    """
    b, e, h, l = p.b, p.e, p.h, p.l
    return 4.0 * l * (3 * h**2 + 8 * l**2 + 4 * e * l) / (4 * b**2 * e + 8 * b**2 * l + 3 * e * h * l)


def amplification_ratio_partials(p: DBMAParams) -> dict:
    """Partial derivatives of R with respect to l, h, e, b as printed in Eq. 8 (1/m).

    Returns {"l", "h", "e", "b"}; the paper claims dR/dl > 0 and dR/dh, dR/de, dR/db < 0.
    """
    b, e, h, l = p.b, p.e, p.h, p.l
    den = (4 * b**2 * e + 8 * b**2 * l + 3 * e * h * l) ** 2
    return {
        "l": 16 * (8 * b**2 * e**2 * l + 3 * b**2 * e * h**2 + 32 * b**2 * e * l**2
                   + 32 * b**2 * l**3 + 3 * e**2 * h * l**2 + 12 * e * h * l**3) / den,
        "h": 12 * l * (8 * b**2 * e * h + 16 * b**2 * h * l - 4 * e**2 * l**2
                       + 3 * e * h**2 * l - 8 * e * l**3) / den,
        "e": -12 * h * l * (4 * b**2 * h + 3 * h**2 * l + 8 * l**3) / den,
        "b": -32 * b * l * (e + 2 * l) * (3 * h**2 + 8 * l**2 + 4 * e * l) / den,
    }


def equivalent_stiffness(p: DBMAParams) -> float:
    """Equivalent ("flexure hinge coupling") stiffness Ke of the DBMA (Eq. 14), N/m.

    Ke = E b^3 d (e + 2 l) / (32 b^2 l^2 + 16 e b^2 l + 6 h^2 l^2 + 32 l^4 + 16 e l^3).
    """
    b, d, e, l = p.b, p.d, p.e, p.l
    return p.E * b**3 * d * (e + 2 * l) / _ke_denominator(p)


def _ke_denominator(p: DBMAParams) -> float:
    b, e, h, l = p.b, p.e, p.h, p.l
    return 32 * b**2 * l**2 + 16 * e * b**2 * l + 6 * h**2 * l**2 + 32 * l**4 + 16 * e * l**3


def equivalent_stiffness_partials(p: DBMAParams) -> dict:
    """Partial derivatives of Ke with respect to l, h, e, b, d as printed in Eq. 15 (N/m^2).

    Returns {"l", "h", "e", "b", "d"}; the paper claims dKe/dl, dKe/dh < 0 and dKe/de,
    dKe/db, dKe/dd > 0. Eq. 15 writes its denominators with
    D' = 16 b^2 l + 8 e b^2 + 3 h^2 l + 16 l^3 + 8 e l^2 (Eq. 14's denominator is 2 l D').
    """
    E, b, d, e, h, l = p.E, p.b, p.d, p.e, p.h, p.l
    dp = 16 * b**2 * l + 8 * e * b**2 + 3 * h**2 * l + 16 * l**3 + 8 * e * l**2
    return {
        "l": -E * b**3 * d * (4 * b**2 * e**2 + 16 * b**2 * e * l + 16 * b**2 * l**2
                              + 12 * e**2 * l**2 + 3 * e * h**2 * l + 48 * e * l**3
                              + 3 * h**2 * l**2 + 48 * l**4) / (l**2 * dp**2),
        "h": -3 * E * b**3 * d * h * (e + 2 * l) / dp**2,
        "e": 3 * E * b**3 * d * h**2 / (2 * dp**2),
        "b": E * b**2 * d * (e + 2 * l) * (16 * b**2 * l + 8 * e * b**2 + 9 * h**2 * l
                                           + 48 * l**3 + 24 * e * l**2) / (2 * l * dp**2),
        "d": E * b**3 * (e + 2 * l) / _ke_denominator(p),
    }


def arm_masses(p: DBMAParams, m4: float = 0.0, m11: float | None = None) -> dict:
    """Masses of the arms that enter Eq. 19 (kg), under this project's reading of Table 1.

    m1 = rho d c e (arms 1, 3, 5, 7, 8, 10, 12, 14: width c, length e between hinges);
    m2 = rho d a ll (arms 2, 6, 9, 13: width a, length ll); m11 = rho d ls e (arm 11: width
    ls; Table 1 lists arm 11 among the arms of length e) unless given; m4: arm 4 is not
    dimensioned anywhere in the paper, so it is 0 unless given (kg).
    """
    if m4 < 0:
        raise ValueError(f"m4 = {m4!r} must be >= 0 (kg)")
    if m11 is None:
        m11 = p.rho * p.d * p.ls * p.e
    elif m11 < 0:
        raise ValueError(f"m11 = {m11!r} must be >= 0 (kg)")
    return {"m1": p.rho * p.d * p.c * p.e, "m2": p.rho * p.d * p.a * p.ll,
            "m4": float(m4), "m11": float(m11)}


def equivalent_mass(R: float, m1: float, m2: float, m4: float, m11: float) -> float:
    """Equivalent mass of the DBMA (Eq. 19), kg.

    me = (1/R^2 + 9/4) m1 + (2/R^2 + 5/4) m2 + m4/2 + 2 m11, with the arm masses in kg and R
    the amplification ratio.
    """
    if R <= 0:
        raise ValueError(f"R = {R!r} must be > 0")
    return (1 / R**2 + 9 / 4) * m1 + (2 / R**2 + 5 / 4) * m2 + m4 / 2 + 2 * m11


def natural_frequency(Ke: float, me: float) -> float:
    """Natural frequency of a single-degree-of-freedom system, fn = sqrt(Ke/me) / (2 pi) (Eq. 11), Hz."""
    if Ke <= 0 or me <= 0:
        raise ValueError(f"Ke = {Ke!r} N/m and me = {me!r} kg must both be > 0")
    return math.sqrt(Ke / me) / (2 * math.pi)


def natural_frequency_eq20(p: DBMAParams, masses: dict | None = None) -> float:
    """Natural frequency of the DBMA (Eq. 20): Eq. 11 with Ke from Eq. 14 and me from Eq. 19, Hz.

    masses: {"m1", "m2", "m4", "m11"} in kg; default ``arm_masses(p)``.
    """
    masses = arm_masses(p) if masses is None else masses
    me = equivalent_mass(amplification_ratio(p), **masses)
    return natural_frequency(equivalent_stiffness(p), me)


def implied_equivalent_mass(Ke: float, fn: float) -> float:
    """Equivalent mass that Eq. 11 needs to give fn (Hz) with stiffness Ke (N/m), kg."""
    return Ke / (2 * math.pi * fn) ** 2


def paper_model_metrics(p: DBMAParams, masses: dict | None = None) -> dict:
    """Eqs. 7, 14, 19, 20 for one design: {"R_eq7", "Ke_eq14", "me_eq19", "fn_eq20"} (SI)."""
    masses = arm_masses(p) if masses is None else masses
    R = amplification_ratio(p)
    Ke = equivalent_stiffness(p)
    me = equivalent_mass(R, **masses)
    return {"R_eq7": R, "Ke_eq14": Ke, "me_eq19": me, "fn_eq20": natural_frequency(Ke, me)}
