"""A small progress line on stderr for long studies: cases done, failed, time left.

It draws only when its stream is a terminal (or when forced), so logs and pipes stay clean.
"""
import sys
import time


def format_duration(seconds: float) -> str:
    """"1h02m", "3m05s" or "42s"."""
    seconds = max(0, round(seconds))
    hours, rest = divmod(seconds, 3600)
    minutes, secs = divmod(rest, 60)
    if hours:
        return f"{hours}h{minutes:02d}m"
    return f"{minutes}m{secs:02d}s" if minutes else f"{secs}s"


def estimated_time_left(done: int, total: int, elapsed_s: float) -> float | None:
    """Seconds left at the mean rate so far (s), None before the first case completes."""
    if done <= 0:
        return None
    return elapsed_s / done * max(total - done, 0)


def format_progress(done: int, failed: int, total: int, elapsed_s: float, width: int = 24) -> str:
    """One progress line, e.g. "[#####-----]  5/10 cases, 1 failed, 12s left"."""
    filled = int(width * done / total) if total else width
    left = estimated_time_left(done, total, elapsed_s)
    eta = "estimating" if left is None else f"{format_duration(left)} left"
    return f"[{'#' * filled}{'-' * (width - filled)}] {done}/{total} cases, {failed} failed, {eta}"


class Progress:
    """Progress of ``total`` cases, drawn on ``stream`` (stderr) when it is a terminal or
    ``enabled`` is True. Call ``update(ok)`` per completed case and ``close()`` at the end."""

    def __init__(self, total: int, stream=None, enabled: bool | None = None):
        self.total = total
        self.stream = sys.stderr if stream is None else stream
        isatty = getattr(self.stream, "isatty", lambda: False)
        self.enabled = isatty() if enabled is None else enabled
        self.done = 0
        self.failed = 0
        self._start = time.perf_counter()
        self._draw()

    def update(self, ok: bool = True) -> None:
        self.done += 1
        self.failed += 0 if ok else 1
        self._draw()

    def close(self) -> None:
        if self.enabled:
            self.stream.write("\n")
            self.stream.flush()

    def _draw(self) -> None:
        if self.enabled:
            line = format_progress(self.done, self.failed, self.total,
                                   time.perf_counter() - self._start)
            self.stream.write("\r" + line + "\033[K")
            self.stream.flush()
