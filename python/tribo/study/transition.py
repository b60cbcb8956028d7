"""The transition roundness eps_t: the smallest roundness at which the particle turns
over.

`find_transition` takes a predicate evaluated on a batch of roundness values at a time
(so that a batch can run in parallel) and
  1. evaluates it on a coarse grid; the first grid value that turns is the upper end of
     the bracket, the grid value below it (which does not turn) the lower end;
  2. shrinks the bracket by multi-section: each round evaluates k equally spaced interior
     points (k = the executor's parallel runs; k = 1 is bisection) and keeps the
     sub-interval between the last non-turning point below the first turning point and
     that turning point; until the bracket is no wider than `width`.
The answer is the final bracket (lo, hi]: eps_t = (lo + hi) / 2 +- (hi - lo) / 2.
The search assumes turning is monotonic inside the bracket; whether the evaluated points
are monotonic (no turning value below a non-turning one) is reported, on the coarse grid
and over every evaluated point.
"""

from dataclasses import dataclass, field
from typing import Callable, Sequence

DECIMALS = 10  # evaluated points are rounded, so that their runs have stable keys


@dataclass
class Transition:
    lo: float | None  # largest evaluated value below hi that does not turn (None: hi is the grid's first)
    hi: float | None  # smallest evaluated value that turns (None: nothing on the grid turns)
    evaluated: dict = field(default_factory=dict)  # value -> turns (bool), every point evaluated
    grid: list = field(default_factory=list)
    rounds: int = 0

    @property
    def found(self) -> bool:
        return self.lo is not None and self.hi is not None

    @property
    def estimate(self) -> float:
        return (self.lo + self.hi) / 2 if self.found else float("nan")

    @property
    def uncertainty(self) -> float:
        return (self.hi - self.lo) / 2 if self.found else float("nan")

    @property
    def monotonic_on_grid(self) -> bool:
        return _monotonic({e: self.evaluated[e] for e in self.grid})

    @property
    def monotonic(self) -> bool:
        return _monotonic(self.evaluated)

    def describe(self) -> str:
        if self.hi is None:
            return f"no turning on the grid (up to {max(self.grid):g})"
        if self.lo is None:
            return f"eps_t <= {self.hi:g} (the smallest grid value already turns)"
        return f"eps_t = {self.estimate:.4f} +- {self.uncertainty:.4f} (bracket ({self.lo:.4f}, {self.hi:.4f}])"


def _monotonic(turns: dict) -> bool:
    flags = [turns[e] for e in sorted(turns)]
    return flags == sorted(flags)  # False ... False True ... True


def find_transition(turns: Callable[[list[float]], Sequence[bool]], grid: Sequence[float],
                    width: float, points_per_round: int = 1) -> Transition:
    """The bracket of the smallest value of `grid`'s range at which `turns` is True."""
    if width <= 0 or points_per_round < 1:
        raise ValueError("width must be > 0 and points_per_round >= 1")
    grid = sorted(round(float(e), DECIMALS) for e in grid)
    result = Transition(lo=None, hi=None, grid=grid)
    result.evaluated.update(zip(grid, map(bool, turns(grid))))
    turning = [e for e in grid if result.evaluated[e]]
    if not turning:
        return result
    result.hi = turning[0]
    below = [e for e in grid if e < result.hi]
    if not below:
        return result
    result.lo = below[-1]

    while result.hi - result.lo > width * (1 + 1e-9):
        lo, hi, k = result.lo, result.hi, points_per_round
        points = [round(lo + (hi - lo) * j / (k + 1), DECIMALS) for j in range(1, k + 1)]
        points = [p for p in dict.fromkeys(points) if lo < p < hi]
        if not points:  # the bracket is at the rounding resolution
            break
        result.evaluated.update(zip(points, map(bool, turns(points))))
        result.rounds += 1
        first_turning = next((p for p in points if result.evaluated[p]), None)
        if first_turning is None:
            result.lo = points[-1]
        else:
            result.hi = first_turning
            result.lo = max([lo] + [p for p in points if p < first_turning])
    return result
