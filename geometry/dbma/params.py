"""Parameters of the double-row bow-type micro-displacement amplifier (DBMA).

Symbols and words are those of the DBMA paper (Micromachines 2020, 11(3), 312, Table 1 and
Eqs. 5-7); values are in SI units (m, Pa, kg/m^3). ``paper_design()`` loads the paper's design
from data/dbma_paper.toml.
"""
from dataclasses import dataclass, fields

from ...data import load_toml
from ...fem import checks
from .. import bounds

MM = 1e-3  # metres per millimetre
OWNER = "DBMAParams"


@dataclass(frozen=True)
class DBMAParams:
    """Dimensions and material of a DBMA (SI units).

    c : width of arms 1, 3, 5, 7, 8, 10, 12, 14 (the inclined arms carrying the hinges) (m)
    a : width of arms 2, 6, 9, 13 (m)
    d : thickness of the amplifier, also the width of the flexure hinge (m)
    l : length of the flexure hinge (m)
    e : length of the arm between its two hinges (Table 1: "length of the arms") (m)
    ls : width of arm 11 (m)
    ll : length of arms 2, 6, 9, 13 (m)
    b : thickness of the flexure hinge (m)
    h : height difference between the two flexure hinges of an arm, h = l1 - l2 (Eq. 5) (m)
    E : elastic modulus of the material (Pa)
    nu : Poisson's ratio of the material (-), not given by the paper
    rho : density of the material (kg/m^3), not given by the paper

    Bounds: every length a finite number in [10 nm, 10 m] (geometry/bounds.py) except h, which
    may also be 0 (h = 0 puts the two hinges on one line, a valid limit of the drawing; the
    analyses need h > 0), at most 10^4 between the largest and smallest length; b < c and
    b < a (the hinge is thinner than the arms it joins);
    h <= c - b (both hinges, each of thickness b, lie within the width c of the arm that
    joins them, so their centre lines are at most c - b apart); E in [1 kPa, 10 TPa];
    -1 < nu < 0.5; rho in [1, 1e5] kg/m^3.
    """

    c: float
    a: float
    d: float
    l: float
    e: float
    ls: float
    ll: float
    b: float
    h: float
    E: float
    nu: float
    rho: float

    def __post_init__(self):
        for f in fields(self):
            object.__setattr__(self, f.name, checks.real(f.name, getattr(self, f.name), OWNER))
        bounds.span(OWNER, bounds.lengths(OWNER, self, ("c", "a", "d", "l", "e", "ls", "ll", "b")))
        bounds.lengths(OWNER, self, ("h",), zero_allowed=("h",))
        for arm in ("c", "a"):
            if not self.b < getattr(self, arm):
                raise checks.InputError("b", self.b, f"< {arm} = {getattr(self, arm)!r} m (hinge "
                                        "thinner than the arm)", OWNER)
        if not self.h <= self.c - self.b:
            raise checks.InputError("h", self.h, f"<= c - b = {self.c - self.b!r} m (both "
                                    "hinges inside the arm width)", OWNER)
        checks.in_range("E", self.E, bounds.MODULUS_RANGE, "Pa", OWNER)
        checks.in_range("nu", self.nu, (-1.0, 0.5), owner=OWNER, closed=False)
        checks.in_range("rho", self.rho, bounds.DENSITY_RANGE, "kg/m^3", OWNER)


def paper_design() -> DBMAParams:
    """The DBMA of the paper: Table 1 with h = 2.6 mm, b = 0.6 mm (Section 4), SI units.

    E is read as 215 GPa (Table 1 prints "215 Mpa", a typo); nu and rho are not in the paper
    and are handbook steel values (data/dbma_paper.toml, [material_assumed]).
    """
    data = load_toml("dbma_paper.toml")
    table, design, material = data["table1"], data["design"], data["material_assumed"]
    lengths = {name: table[f"{name}_mm"] * MM for name in ("c", "a", "d", "l", "e", "ls", "ll")}
    return DBMAParams(**lengths, b=design["b_mm"] * MM, h=design["h_mm"] * MM,
                      E=table["E_GPa_read"] * 1e9, nu=material["nu"],
                      rho=material["rho_kg_m3"])
