"""What a study is checked for before any case runs, and a stored case before it is reused.

Before: every parameter it names (base, grid, cases, sample ranges, tolerances) is one the
mechanism's evaluate declares (validate.declare), every option one it takes (the
``[tolerances.confirm]`` options too, not only after the screening has run), every plot's
parameter one the study gives. After: a stored "ok" row is reused only if it passes the
checks of a fresh result (validate.result_problems) and has every metric the study asks for
(its plots' metrics and overlays, its tolerances' metrics); otherwise it is computed again,
and a warning line on stderr says which and why.
"""
import sys
from dataclasses import replace

from .validate import (check_metric_names, check_parameter_names, nearest, normalise_options,
                       result_problems)


def study_parameter_names(study) -> list[tuple[str, str]]:
    """(where, name) of every parameter the study names, in file order."""
    named = [(f"base.{k}", k) for k in study.base]
    named += [(f"grid.{k}", k) for k in study.grid]
    named += [(f"cases[{i}].{k}", k) for i, case in enumerate(study.cases) for k in case]
    if study.sample is not None:
        named += [(f"sample.ranges.{k}", k) for k in study.sample.ranges]
    if study.tolerances is not None:
        named += [(f"tolerances.parameters.{k}", k) for k in study.tolerances.parameters]
    return named


def required_metrics(study) -> tuple:
    """The metrics the study asks for: its plots' metrics and overlays, its tolerances'."""
    names = [m for p in study.plots for m in (p.metric, *p.overlay)]
    if study.tolerances is not None:
        names += list(study.tolerances.metrics)
    return tuple(dict.fromkeys(names))


def check_study(study, evaluate):
    """``study`` with its options normalised (validate.normalise_options), after refusing
    (ValueError naming the key, the known names and the nearest) any name it cannot mean."""
    options = normalise_options(evaluate, study.options, study.mechanism)
    confirm = study.tolerances.confirm if study.tolerances is not None else None
    if confirm:
        normalise_options(evaluate, {**options, **confirm}, study.mechanism,
                          where="tolerances.confirm")
    named = study_parameter_names(study)
    check_parameter_names(evaluate, named, study.mechanism)
    metrics = [(f"plots[{i}].{'metric' if k == 0 else 'overlay'}", m)
               for i, p in enumerate(study.plots) for k, m in enumerate((p.metric, *p.overlay))]
    if study.tolerances is not None:
        metrics += [("tolerances.metrics", m) for m in study.tolerances.metrics]
    check_metric_names(evaluate, metrics, study.mechanism)
    given = sorted({name for _, name in named})
    for i, plot in enumerate(study.plots):
        if plot.parameter not in given:
            raise ValueError(f"plots[{i}].parameter = {plot.parameter!r} is no parameter the "
                             f"study gives (base, grid, cases, sample, tolerances): "
                             f"{', '.join(given) or 'none'}{nearest(plot.parameter, given)}")
    return replace(study, options=options)


def stale_rows(store, keys, evaluate, required=()) -> dict:
    """{key: [problems]} of the stored "ok" rows among ``keys`` that may not be reused."""
    return {case.key: problems for case in store.results(keys)
            if (problems := result_problems(case.metrics, evaluate, required))}


def warn_stale(stale: dict, store_path, limit: int = 5) -> None:
    """One warning line on stderr per row computed again (the first ``limit``, then a count)."""
    for key, problems in list(stale.items())[:limit]:
        print(f"flexfem: warning: {store_path}: stored case {key[:12]} is computed again: "
              f"{'; '.join(problems)}", file=sys.stderr)
    if len(stale) > limit:
        print(f"flexfem: warning: {store_path}: {len(stale) - limit} more stored cases are "
              "computed again for the same reasons", file=sys.stderr)
