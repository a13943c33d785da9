"""The [material] table of a model file: a library material, or E and nu (rho and the
strengths optional), checked against what solids have."""
import math

from ...fem import checks
from ...fem.materials import Material, material, material_names
from .tables import Locator, check_keys, located

#: The largest yield strain (yield_strength / E) a model file's material may have: metals,
#: silicon and engineering polymers lie below ~3 %; above it is a units mistake (kPa for GPa),
#: and the continuum's St. Venant-Kirchhoff law holds to a few per cent of strain only.
YIELD_STRAIN_LIMIT = 0.1

#: What solids have (elastomers to diamond, aerogels to osmium): a model file's value outside
#: is a units mistake (MPa for Pa, g/cm^3 for kg/m^3) or overflows the solve.
PHYSICAL = {"E": (1e3, 1e13, "Pa"), "rho": (1.0, 1e5, "kg/m^3"),
            "yield_strength": (1e3, 1e11, "Pa"), "ultimate_strength": (1e3, 1e11, "Pa"),
            "fatigue_strength": (1e3, 1e11, "Pa"), "fatigue_cycles": (1.0, 1e12, "cycles")}

def parse_material(raw, loc: Locator) -> Material:
    """A library material by ``name`` (keys given override it) or E and nu (rho,
    yield_strength, ultimate_strength, fatigue_strength with fatigue_cycles optional), Pa
    and kg/m^3. Without rho the material serves static analyses (:func:`check_density`)."""
    keys = ("name", "E", "nu", "rho", "yield_strength", "ultimate_strength",
            "fatigue_strength", "fatigue_cycles")
    raw = dict(check_keys(raw, keys, loc, "material"))
    name = raw.pop("name", None)
    if name is not None and not isinstance(name, str):
        raise loc.error(f"[material] name = {name!r} must be a string", "material", "name")
    for key in raw:
        located(checks.real, raw, key, loc, "material")
    if name in material_names():
        base = material(name).as_dict()
        values = {**{k: base[k] for k in keys[1:]}, **raw}
        source = material(name).source
        values["fatigue_source"] = (material(name).fatigue_source if not set(raw) & {
            "fatigue_strength", "fatigue_cycles"} else f"model file {loc.path}")
    else:
        missing = [k for k in ("E", "nu") if k not in raw]
        if missing:
            known = ", ".join(material_names())
            msg = (f"[material] name = {name!r} is not in the library ({known}); give E and nu "
                   f"(rho for frequencies; missing: {', '.join(missing)})" if name is not None
                   else f"[material] needs a library name ({known}) or E and nu (rho for "
                   f"frequencies; missing: {', '.join(missing)})")
            raise loc.error(msg, "material", "name" if name is not None else None)
        values, source = {"rho": None, **raw}, f"model file {loc.path}"
        if "fatigue_strength" in raw:
            values["fatigue_source"] = source
    for key, (low, high, unit) in PHYSICAL.items():
        if key in raw and not low <= values[key] <= high:
            raise loc.error(f"[material] {key} = {values[key]!r} is outside what solids have "
                            f"({low:g} to {high:g} {unit}); check the units ({unit})",
                            "material", key)
    strain = values.get("yield_strength", math.inf) / values["E"]
    if math.isfinite(strain) and strain > YIELD_STRAIN_LIMIT and {"E", "yield_strength"} & set(raw):
        raise loc.error(f"[material] yield_strength / E = {strain:.3g}: a strain at yield above "
                        f"{YIELD_STRAIN_LIMIT:.0%} is no flexure material's (a unit mistake: "
                        "E and the strengths are in Pa); check E and yield_strength",
                        "material", "E" if "E" in raw else "yield_strength")
    try:
        return Material(name=name or "user", source=source, **values)
    except ValueError as error:
        raise loc.error(f"[material]: {error}", "material") from None


def check_density(parts: dict, loc: Locator) -> None:
    """Refuse, before anything is solved, an [analysis] that needs masses (modes, harmonic)
    of a [material] without rho."""
    analysis = parts["analysis"]
    asked = [name for name, on in (("modes", analysis.modes),
                                   ("harmonic", analysis.harmonic)) if on]
    if asked and parts["material"].rho is None:
        raise loc.error(f"[analysis] {' and '.join(asked)} need{'s' * (len(asked) == 1)} the "
                        "material's density: add rho "
                        "(kg/m^3) to [material]", "material")
