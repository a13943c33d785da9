"""ZDT1 (Zitzler, Deb and Thiele 2000), a test-only mechanism for front searches
(--allow-code): x_i in [0, 1], f1 = x1, g = 1 + 9 mean(x_2..x_n), f2 = g (1 - sqrt(f1 / g));
its Pareto front is f2 = 1 - sqrt(f1), f1 in [0, 1], where x_2..x_n = 0."""
import math

N = 5


def evaluate(params: dict) -> dict:
    x = [float(params[f"x{i}"]) for i in range(1, N + 1)]
    g = 1 + 9 * sum(x[1:]) / (N - 1)
    f1 = x[0]
    return {"f1": f1, "f2": g * (1 - math.sqrt(f1 / g)), "x1_plus_x2": x[0] + x[1]}
