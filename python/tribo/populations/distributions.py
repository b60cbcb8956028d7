"""Distributions of a feed's variables, written as text (on the command line, in a feed
description) and drawn with numpy's seeded generator.

    0.6                     a fixed value
    uniform:0.3:1           uniform between the two ends
    normal:0.6:0.1          normal with mean and standard deviation
    lognormal:1e-3:0.4      log-normal with median and the standard deviation of its log
    choice:0.3,0.6,1.0      one of the values, each as likely

`Distribution.draw(rng, n)` draws n values; what is drawn depends only on the generator's
state, so a population drawn from the same seed is the same population.
"""

import math
from dataclasses import dataclass

import numpy as np

from ..fmu.names import format_number

KINDS = ("uniform", "normal", "lognormal", "choice")


class DistributionError(ValueError):
    """A distribution text that does not parse (the message names it and what is expected)."""


@dataclass(frozen=True)
class Distribution:
    kind: str  # "fixed" or one of KINDS
    args: tuple

    def draw(self, rng: np.random.Generator, n: int) -> np.ndarray:
        if self.kind == "fixed":
            return np.full(n, self.args[0])
        if self.kind == "uniform":
            return rng.uniform(self.args[0], self.args[1], n)
        if self.kind == "normal":
            return rng.normal(self.args[0], self.args[1], n)
        if self.kind == "lognormal":
            return rng.lognormal(math.log(self.args[0]), self.args[1], n)
        return rng.choice(np.array(self.args), n)

    def text(self) -> str:
        """The distribution as it is written, each number in full (reads back the same)."""
        if self.kind == "fixed":
            return format_number(self.args[0])
        sep = "," if self.kind == "choice" else ":"
        return f"{self.kind}:" + sep.join(format_number(a) for a in self.args)


def parse(name: str, text) -> Distribution:
    """The distribution of the variable `name` written as `text` (or a number)."""
    if isinstance(text, (int, float)) and not isinstance(text, bool):
        return _fixed(name, float(text))
    text = str(text).strip()
    kind, sep, rest = text.partition(":")
    if not sep:
        try:
            return _fixed(name, float(text))
        except ValueError:
            raise DistributionError(f"{name} {text!r}: expected a number or "
                                    f"{'|'.join(KINDS)}:... (e.g. uniform:0.3:1)") from None
    if kind not in KINDS:
        raise DistributionError(f"{name} {text!r}: unknown distribution {kind!r} "
                                f"(one of {', '.join(KINDS)})")
    try:
        args = tuple(float(a) for a in rest.split("," if kind == "choice" else ":"))
    except ValueError:
        raise DistributionError(f"{name} {text!r}: the arguments must be numbers") from None
    if not all(math.isfinite(a) for a in args):
        raise DistributionError(f"{name} {text!r}: the arguments must be finite")
    wanted = {"uniform": 2, "normal": 2, "lognormal": 2}.get(kind)
    if wanted is not None and len(args) != wanted:
        raise DistributionError(f"{name} {text!r}: {kind} takes {wanted} numbers, got {len(args)}")
    if kind == "uniform" and not args[0] < args[1]:
        raise DistributionError(f"{name} {text!r}: uniform:LOW:HIGH needs LOW < HIGH")
    if kind in ("normal", "lognormal") and not args[1] > 0:
        raise DistributionError(f"{name} {text!r}: the spread must be > 0")
    if kind == "lognormal" and not args[0] > 0:
        raise DistributionError(f"{name} {text!r}: the median of a lognormal must be > 0")
    if kind == "choice" and not args:
        raise DistributionError(f"{name} {text!r}: choice needs at least one value")
    return Distribution(kind, args)


def _fixed(name, value) -> Distribution:
    if not math.isfinite(value):
        raise DistributionError(f"{name} {value!r}: must be a finite number")
    return Distribution("fixed", (value,))
