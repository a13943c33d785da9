"""Study values checked and normalised before they are hashed into case keys.

A case key is the hash of the values a study gives (store.case_key), so two spellings of one
design must become one value first, and a value the mechanism cannot take must be refused by
name before anything runs: ``dim = 2.0`` is the integer option 2 (``dim = 2.5`` is refused),
a number written as a string (``b = "0.6e-3"``) is refused rather than hashed as another case,
an option the mechanism's evaluate does not declare is refused. The declared options and their
types are read from the evaluate's signature: each keyword parameter's default (an int, float
or bool) or its annotation (``int | None``) gives its type; an annotation
``Literal["continuum", "beam"]`` lists the values an option may take.
"""
import dataclasses
import difflib
import fnmatch
import functools
import inspect
import math
import numbers
import types
import typing

KINDS = (bool, int, float, str)


def _kind(parameter: inspect.Parameter):
    if typing.get_origin(parameter.annotation) is typing.Literal:
        return parameter.annotation
    default = parameter.default
    if default is not inspect.Parameter.empty and default is not None:
        return next((k for k in KINDS if isinstance(default, k)), None)
    annotation = parameter.annotation
    if isinstance(annotation, (types.UnionType,)) or typing.get_origin(annotation) is typing.Union:
        annotation = next((a for a in typing.get_args(annotation) if a is not type(None)), None)
    return annotation if annotation in KINDS else None


def declared_options(evaluate) -> tuple[dict, bool]:
    """({option: type or None}, accepts_any) of ``evaluate(params, **options)``; options a
    functools.partial binds (a model file's path) are not the study's to set."""
    try:
        parameters = list(inspect.signature(evaluate).parameters.values())[1:]
    except (TypeError, ValueError):  # no signature: accept anything, as before
        return {}, True
    bound = set(evaluate.keywords) if isinstance(evaluate, functools.partial) else set()
    accepts_any = any(p.kind is p.VAR_KEYWORD for p in parameters)
    options = {p.name: _kind(p) for p in parameters
               if p.kind in (p.POSITIONAL_OR_KEYWORD, p.KEYWORD_ONLY) and p.name not in bound}
    return options, accepts_any


def _number_string(value) -> bool:
    if not isinstance(value, str):
        return False
    try:
        float(value)
    except ValueError:
        return False
    return True


def check_value(where: str, value) -> None:
    """Refuse a number written as a string (``"0.6e-3"``), anywhere in a study's values."""
    if _number_string(value):
        raise ValueError(f"{where} = {value!r} is a number written as a string: write it "
                         "without quotes (a string would be another case)")
    if isinstance(value, numbers.Complex) and not isinstance(value, numbers.Real):
        raise ValueError(f"{where} = {value!r} must be a real number")


def _normalise(where: str, value, kind):
    if typing.get_origin(kind) is typing.Literal:
        if value not in typing.get_args(kind):
            raise ValueError(f"{where} = {value!r} must be one of {list(typing.get_args(kind))}")
        return value
    if kind is bool:
        if not isinstance(value, bool):
            raise ValueError(f"{where} = {value!r} must be true or false")
        return value
    if kind in (int, float):
        if isinstance(value, bool) or not isinstance(value, numbers.Real):
            raise ValueError(f"{where} = {value!r} must be a number"
                             + (" (write it without quotes)" if _number_string(value) else ""))
        if not math.isfinite(value):
            raise ValueError(f"{where} = {value!r} must be finite")
        if kind is int:
            if value != int(value):
                raise ValueError(f"{where} = {value!r} must be an integer")
            return int(value)
        return float(value)
    if kind is str and not isinstance(value, str):
        raise ValueError(f"{where} = {value!r} must be a string")
    check_value(where, value)
    return value


def normalise_options(evaluate, options: dict, mechanism: str, where: str = "options") -> dict:
    """``options`` with each value of its declared type (an integral 2.0 for an int option
    is 2); ValueError naming ``options.<name>`` for an unknown option (one the signature
    lacks, or that its ``**options`` do not take where :func:`declare` says which) or a
    value of the wrong type."""
    declared, accepts_any = declared_options(evaluate)
    extra = _declared(evaluate, "study_options")  # what its **options take, if it says
    out = {}
    for name, value in options.items():
        if name not in declared and (not accepts_any or extra is not None and name not in extra):
            known = sorted(declared) + sorted(extra or ())
            raise ValueError(f"{where}.{name} is not an option of mechanism {mechanism!r}; "
                             f"its options: {known}{nearest(name, known)}")
        out[name] = _normalise(f"{where}.{name}", value, declared.get(name))
    return out


def require_finite(values: dict, what: str) -> dict:
    """``values`` if every real number in it is finite, else ValueError naming those that
    are not: a NaN or an infinity is never printed or stored as a result."""
    bad = sorted(k for k, v in values.items() if isinstance(v, numbers.Real)
                 and not isinstance(v, bool) and not math.isfinite(v))
    if bad:
        raise ValueError(f"{what}: result not finite: "
                         + ", ".join(f"{k} = {values[k]}" for k in bad))
    return values


def declare(parameters=None, options=None, positive=(), metrics=None):
    """Decorate a mechanism's ``evaluate`` with what the engine checks around it, so that a
    misspelled name is refused before any case runs and a stored row is reused only if it
    passes the checks of a fresh one. ``parameters``: its parameter names (a dataclass: its
    fields; an iterable of names; or a callable taking the keywords a functools.partial
    binds, e.g. a model file's ``file``, and returning them, or None where it cannot tell); ``options``: the same for the
    names its ``**options`` take (a model file's 'table.key'); ``positive``: metric names or
    fnmatch patterns ("stiffness_*", "f*_hz") that must be > 0 (stiffnesses, frequencies: positive by definition
    in its analyses); ``metrics``: the metric names it may return, names or fnmatch patterns
    (the same kinds as ``parameters``), so that a study's, a front's or a convergence
    study's misspelled metric is refused before any case runs. An evaluate declaring nothing
    is checked by its signature only."""
    def mark(evaluate):
        evaluate.study_parameters = parameters
        evaluate.study_metrics = metrics
        evaluate.study_options = options
        evaluate.positive_metrics = tuple(positive)
        return evaluate
    return mark


def _declared(evaluate, attribute: str):
    func, bound = evaluate, {}
    if isinstance(evaluate, functools.partial):
        func, bound = evaluate.func, dict(evaluate.keywords)
    source = getattr(func, attribute, None)
    if source is None:
        return None
    if dataclasses.is_dataclass(source) and isinstance(source, type):
        return {f.name for f in dataclasses.fields(source)}
    names = source(**bound) if callable(source) else source
    return None if names is None else set(names)


def known_parameters(evaluate) -> set | None:
    """The parameter names ``evaluate`` declares (:func:`declare`), None if it declares none."""
    return _declared(evaluate, "study_parameters")


def check_metric_names(evaluate, named, mechanism: str) -> None:
    """Refuse the first of ``named`` ((where, metric) pairs: 'plots[0].metric', 'R') that is
    none of the metrics ``evaluate`` declares (:func:`declare`; names or fnmatch patterns),
    with the known ones and the nearest."""
    known = _declared(evaluate, "study_metrics")
    if known is None:
        return
    for where, name in named:
        if not any(fnmatch.fnmatchcase(str(name), k) for k in known):
            exact = sorted(k for k in known if not any(c in k for c in "*?["))
            raise ValueError(f"{where} = {name!r} is no metric of mechanism {mechanism!r}; "
                             f"its metrics: {', '.join(sorted(known))}{nearest(name, exact)}")


def nearest(name, known) -> str:
    """'; did you mean 'X'?' for the closest of ``known`` to ``name`` (difflib), or ''."""
    close = difflib.get_close_matches(str(name), sorted(map(str, known)), n=1, cutoff=0.6)
    return f"; did you mean {close[0]!r}?" if close else ""


def check_parameter_names(evaluate, named, mechanism: str) -> None:
    """Refuse the first of ``named`` ((where, name) pairs: 'grid.L', 'L') that names no
    parameter ``evaluate`` declares, with the known names and the nearest: a misspelled
    name would otherwise run the mechanism's default for the parameter meant, unchanged."""
    known = known_parameters(evaluate)
    if known is None:
        return
    for where, name in named:
        if name not in known:
            raise ValueError(f"{where} names no parameter of mechanism {mechanism!r}; its "
                             f"parameters: {', '.join(sorted(known)) or 'none'}"
                             f"{nearest(name, known)}")


def result_problems(metrics: dict, evaluate=None, required=()) -> list[str]:
    """Why ``metrics`` (an "ok" case's, fresh or stored) cannot stand as a result: none at
    all, a metric the study asks for (``required``) missing, a number that is not finite,
    a metric ``evaluate`` declares positive (:func:`declare`) that is not > 0. [] if none."""
    if not metrics:
        return ["it has no metrics"]
    reasons = metrics.get("not_available")
    why = f" (not available: {reasons})" if isinstance(reasons, str) and reasons else ""
    problems = [f"metric {m!r} is missing{why}" for m in required if m not in metrics]
    func = evaluate.func if isinstance(evaluate, functools.partial) else evaluate
    patterns = getattr(func, "positive_metrics", ())
    for name, value in metrics.items():
        if not isinstance(value, numbers.Real) or isinstance(value, bool):
            continue
        if not math.isfinite(value):
            problems.append(f"{name} = {value} is not finite")
        elif not value > 0 and any(fnmatch.fnmatchcase(name, p) for p in patterns):
            problems.append(f"{name} = {value:g} must be > 0")
    return problems
