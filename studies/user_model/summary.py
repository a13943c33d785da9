"""The human summary of a model file's analysis (what ``flexfem analyze`` prints and
:meth:`~flexfem.studies.user_model.model_report.Report.summary` returns): one line a quantity,
numbers to 4 significant digits, lengths in the unit asked (``display_units``: m, mm or um;
stiffness per that length), forces in N, stresses in MPa, frequencies in Hz."""


#: Length units of the human summary (--units): metres by default; --json stays SI.
LENGTH_UNITS = {"m": 1.0, "mm": 1e3, "um": 1e6}


def _vector(v, unit: str, scale: float = 1.0) -> str:
    return "(" + ", ".join(f"{c * scale:.4g}" for c in v) + f") {unit}"


def _lengths(result: dict) -> tuple[str, float]:
    """(unit, scale from m) of the summary's lengths."""
    unit = result.get("display_units", "m")
    return unit, LENGTH_UNITS[unit]


def summarize(result: dict) -> str:
    """The human summary of an analysis dict (:func:`~.analysis.analyze_model`'s), one line a
    quantity; lengths in ``result["display_units"]`` (m where absent)."""
    m, to = _lengths(result)
    lines = [f"{result['model']}: {result['dim']}-D, {result['dofs']} DOFs, solver "
             f"{result['solver']}, element size h = {result['h'] * to:.4g} {m}"]
    if result.get("mesh_choice") not in (None, "default"):
        lines.append(f"mesh: {result['mesh_choice']}" if result["mesh_choice"] != "given" else
                     f"mesh: size_factor {result['size_factor']:g} (given)")
    vm = result["max_von_mises"]
    where = _vector(result["max_von_mises_location"], m, to)
    strength = result["yield_strength"]
    share = (f" ({100 * vm / strength:.4g} % of yield)" if strength is not None and vm > 0 else
             " (% of yield not available: needs yield_strength)" if strength is None else "")
    lines.append(f"max von Mises stress {vm / 1e6:.4g} MPa at {where}{share}")
    for group, u in result["mean_displacement"].items():
        lines.append(f"mean displacement of {group!r}: {_vector(u, m, to)}")
    for group, f in result["reactions"].items():
        lines.append(f"reaction on {group!r}: {_vector(f, 'N')}")
    for group, by_axis in result["stiffness"].items():
        for axis, k in by_axis.items():
            lines.append(f"stiffness of {group!r} along {axis}: {k / to:.4g} N/{m}")
    if result.get("stroke_limit_yield") is not None or "stroke_group" in result:
        lines += _stroke_lines(result)
    if "frequencies_hz" in result:
        lines.append("natural frequencies: " + ", ".join(f"{f:.4g}" for f in
                                                          result["frequencies_hz"]) + " Hz")
    if "compliance" in result:
        c = result["compliance"]
        lines.append(f"compliance of {c['group']!r} (rigid face at {_vector(c['point_m'], m, to)}"
                     "): diagonal " + _vector([r[i] for i, r in enumerate(c["matrix"])],
                                              "(m/N, rad/(N m))"))
    if "buckling" in result:
        lines.append("buckling load factors: " + ", ".join(
            f"{f:.4g}" for f in result["buckling"]["load_factors"]))
    if "harmonic" in result:
        h = result["harmonic"]
        lines.append(f"harmonic response of {h['group']!r} along {h['component']} "
                     f"({100 * h['damping']:.3g} % damping): static {h['static'] * to:.4g} {m}, "
                     "resonances " + (", ".join(f"{f:.4g}" for f in h["resonances_hz"])
                                      or "none in range") + " Hz")
    if "nonlinear" in result:
        nl = result["nonlinear"]
        for group, u in nl["mean_displacement"].items():
            lines.append(f"large deflection ({nl['steps']} steps), mean displacement of "
                         f"{group!r}: {_vector(u, m, to)}")
    return "\n".join(lines + _output_lines(result))


def _output_lines(result: dict) -> list[str]:
    """The [outputs] (and, with steps, at the final step) and the rotations of the bodies
    and faces observed."""
    lines, why = [], result.get("not_available", {})
    m, to = _lengths(result)
    for name, value in result.get("outputs", {}).items():
        lines.append(f"output {name} = {value:.6g}" if value is not None else
                     f"output {name}: not available: {why.get('outputs.' + name, '')}")
    for name, value in result.get("nonlinear", {}).get("outputs", {}).items():
        if value is not None:
            lines.append(f"large deflection, output {name} = {value:.6g}")
    for group, o in result.get("observations", {}).items():
        turns = {k: v for k, v in o.items() if k.startswith("r") and v is not None}
        if turns and group not in result["mean_displacement"]:
            u = _vector([v for k, v in o.items() if k[0] == "u"], m, to)
            lines.append(f"observed {group!r}: u = {u}"
                         + "".join(f", {k} = {v:.4g} rad" for k, v in turns.items()))
    return lines


def _stroke_lines(result: dict) -> list[str]:
    """The stroke limits in a designer's words."""
    group, n = result["stroke_group"], result.get("safety_factor", 1.0)
    lines = []
    if "stroke_limit_where" not in result:  # no stress to size it by
        return [f"no stroke limit of {group!r}: sized by {result['stroke_stress_basis']}"]
    missing = result.get("not_available", {})
    if result["stroke_limit_yield"] is not None:
        lines.append(f"stroke of {group!r} to yield (safety factor {n:g}): "
                     f"{result['stroke_limit_yield'] * 1e3:.4g} mm")
    else:
        lines.append(f"stroke of {group!r} to yield: not available: "
                     f"{missing.get('stroke_limit_yield', 'no yield strength')}")
    if result["stroke_limit_fatigue"] is not None:
        mean = (f" about a mean of {result['mean_stroke'] * 1e3:.4g} mm"
                if result["mean_stroke"] else "")
        lines.append(f"stroke amplitude of {group!r} for {result['fatigue_cycles']:.3g} cycles "
                     f"({result['fatigue_criterion']}{mean}): "
                     f"{result['stroke_limit_fatigue'] * 1e3:.4g} mm")
    else:
        lines.append(f"fatigue-limited stroke amplitude of {group!r}: not available: "
                     f"{missing.get('stroke_limit_fatigue', 'no fatigue data')}")
    lines.append(f"  sized by the {result['stroke_stress_basis']}, at "
                 f"{_vector(result['stroke_limit_where'], *_lengths(result))}")
    if result.get("stroke_limit_basis"):
        lines.append(f"  stroke limits: {result['stroke_limit_basis']}" + _departed(result))
    return lines


def _departed(result: dict) -> str:
    """How far the large-deflection path departs from linear at the linear yield stroke, and
    which of force, the groups' displacement ('output'), peak stress and [outputs] departed."""
    check = result.get("stroke_check")
    if not check:
        return ""
    d = check["departure"]
    named = "".join(f", {name} {100 * v:+.1f} %"
                    for name, v in check.get("output_departure", {}).items())
    departed = ", ".join(check.get("departed", [])) or "none"
    return (f" (at {check['at_stroke'] * 1e3:.4g} mm the {check['model']} model's force, "
            f"outputs and peak stress depart from linear by {100 * d['force']:+.1f} %, "
            f"{100 * d['output']:.1f} %, {100 * d['stress']:+.1f} %{named}; beyond 5 %: "
            f"{departed})")
