"""One comparison of a flexfem number with a reference, and the one relative difference.

Every row a report prints beside a source is a :class:`Comparison`: the quantity, flexfem's
value, the reference, its unit, where the reference comes from and of which kind it is, the
difference, the tolerance it is judged by and the verdict. The kinds:

- ``published``: a number the source prints (a table, a figure read, a measured value);
- ``derived``: a published formula evaluated by flexfem for the same design;
- ``calibrated``: fitted on the source, shown apart, never as agreement;
- ``input``: a number the run was given; never judged (and kept out of headline tables).

Angles and percentages are compared by their absolute difference (degrees, percentage
points): a relative difference of an angle depends on where its zero is.
"""
from dataclasses import asdict, dataclass
import math

KINDS = ("published", "derived", "calibrated", "input")
ABSOLUTE_UNITS = ("deg", "%")


def rel_diff(value: float, reference: float) -> float:
    """(value - reference) / |reference|; nan when the reference is 0 or not finite."""
    if not (isinstance(reference, (int, float)) and math.isfinite(reference)) or reference == 0:
        return math.nan
    return (value - reference) / abs(reference)


@dataclass(frozen=True)
class Comparison:
    """flexfem's ``value`` beside ``reference`` (both in ``unit``).

    source : where the reference is printed or how it was obtained ("Table III", "Eq. 20")
    kind : one of KINDS (see the module)
    tolerance : the largest difference judged as agreement: relative (a fraction) for most
        units, absolute in ``unit`` for degrees and percentages; None: not judged
    headline : True for the few rows that summarise a source document
    limit : "upper" or "lower" when the reference is a bound the value must respect (a design
        requirement, not a value to match); the verdict is then 'within limit' or 'beyond limit'
    """

    quantity: str
    value: float
    reference: float
    unit: str
    source: str
    kind: str = "published"
    tolerance: float | None = None
    note: str = ""
    headline: bool = False
    limit: str = ""

    def __post_init__(self):
        if self.limit not in ("", "upper", "lower"):
            raise ValueError(f"Comparison({self.quantity!r}).limit = {self.limit!r}; "
                             "'', 'upper' or 'lower'")
        if self.kind not in KINDS:
            raise ValueError(f"Comparison({self.quantity!r}).kind = {self.kind!r}; one of {KINDS}")
        if self.tolerance is not None and not self.tolerance >= 0:
            raise ValueError(f"Comparison({self.quantity!r}).tolerance = {self.tolerance!r} "
                             "must be >= 0 or None")
        object.__setattr__(self, "value", float(self.value))
        object.__setattr__(self, "reference", float(self.reference))

    @property
    def absolute(self) -> bool:
        """True when the difference is absolute (angles, percentages)."""
        return self.unit in ABSOLUTE_UNITS

    @property
    def difference(self) -> float:
        """value - reference (in ``unit``) when absolute, else the relative difference."""
        if self.absolute:
            return self.value - self.reference
        return rel_diff(self.value, self.reference)

    @property
    def verdict(self) -> str:
        """'agrees', 'differs', 'within limit', 'beyond limit', 'calibrated', 'input' or
        'not judged'."""
        if self.kind in ("calibrated", "input"):
            return self.kind
        if self.limit:
            below = self.value <= self.reference
            return "within limit" if below == (self.limit == "upper") else "beyond limit"
        if self.tolerance is None or not math.isfinite(self.difference):
            return "not judged"
        return "agrees" if abs(self.difference) <= self.tolerance else "differs"

    def to_row(self) -> dict:
        """A JSON-able row: the fields, flexfem's value as 'flexfem', the difference (with
        its kind, 'relative' or 'absolute') and the verdict."""
        row = asdict(self)
        row["flexfem"] = row.pop("value")
        row.update(difference=self.difference,
                   difference_kind="absolute" if self.absolute else "relative",
                   verdict=self.verdict)
        return row


def rows(comparisons) -> list[dict]:
    """The JSON-able rows of a list of Comparisons."""
    return [c.to_row() for c in comparisons]
