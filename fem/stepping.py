"""The one step driver of every nonlinear solve (continuum, planar and spatial beam): a
fraction 0 -> 1 of the path in equal steps, a failed step halved, a good run of steps let
grow back."""


class StepFailed(Exception):
    """A step's Newton iterations failed: ``reason`` (words) and ``history`` (relative
    residuals of the attempt)."""

    def __init__(self, reason, history):
        super().__init__(reason)
        self.reason, self.history = reason, history


def march(advance, steps: int, min_step: float, failed) -> int:
    """Step the fraction t 0 -> 1 in ``steps`` equal increments; returns the number of cuts.

    ``advance(t, dt, cuts_here)`` tries to reach t + dt from the last accepted state
    (``cuts_here``: the cuts since it; 0 on a first try), accepts it and returns whether the
    solve stops there, or raises StepFailed. A failed step is halved; when half of it would
    be below ``min_step``, ``failed(t, dt, cuts, failure)`` makes the error raised. After
    two good steps in a row a cut step doubles, up to 1 / ``steps``."""
    nominal = dt = 1.0 / steps
    t, cuts, good, cuts_here = 0.0, 0, 0, 0
    while t < 1.0 - 1e-12:
        dt = min(dt, 1.0 - t)
        try:
            stop = advance(t, dt, cuts_here)
        except StepFailed as failure:
            if dt / 2 < min_step * (1 - 1e-9):
                raise failed(t, dt, cuts, failure) from None
            dt, cuts, good, cuts_here = dt / 2, cuts + 1, 0, cuts_here + 1
            continue
        t, cuts_here = t + dt, 0
        if stop:
            break
        good += 1
        if good >= 2 and dt < nominal:
            dt, good = min(2 * dt, nominal), 0
    return cuts
