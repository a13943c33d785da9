"""The Ishigami function, a test-only mechanism (flexfem sweep --allow-code): the standard
check of a global sensitivity analysis, with analytic Sobol indices (Ishigami and Homma 1990;
Sobol' and Levitan 1999). y = sin x1 + a sin^2 x2 + b x3^4 sin x1, x_i uniform on [-pi, pi]."""
import math

A, B = 7.0, 0.1


def evaluate(params: dict) -> dict:
    x1, x2, x3 = (float(params[k]) for k in ("x1", "x2", "x3"))
    return {"y": math.sin(x1) + A * math.sin(x2) ** 2 + B * x3 ** 4 * math.sin(x1)}


def analytic_indices() -> tuple[dict, dict]:
    """(first-order, total-order) Sobol indices {name: value}."""
    pi = math.pi
    v1 = 0.5 * (1 + B * pi ** 4 / 5) ** 2
    v2 = A ** 2 / 8
    v13 = 8 * B ** 2 * pi ** 8 / 225
    total = v1 + v2 + v13
    return ({"x1": v1 / total, "x2": v2 / total, "x3": 0.0},
            {"x1": (v1 + v13) / total, "x2": v2 / total, "x3": v13 / total})
