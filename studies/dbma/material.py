"""The DBMA's material: the paper's modulus, with the properties it does not give."""
from ...fem import Material, material
from ...geometry.dbma.params import DBMAParams


def dbma_material(p: DBMAParams) -> Material:
    """Steel with the paper's E and the assumed nu, rho; the yield strength is not in the paper:
    that of structural steel (data/materials.toml) is used for the safety factor."""
    return Material("dbma_steel", p.E, p.nu, p.rho, material("structural_steel").yield_strength,
                    "E: DBMA paper Table 1 (215 GPa); nu, rho, yield: structural_steel")
