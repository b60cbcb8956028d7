"""The commands' parser: errors in one line, no prefix matching, negative numbers read as
values; with the standard library only, so that `tribo` answers --help and a mistake in
its command line without importing a job's libraries."""

import argparse
import re


class OneLineParser(argparse.ArgumentParser):
    """argparse, with a usage error in one line (no usage block), options only by their
    full names (`--tilt` is not taken for `--tilt-deg`), and a negative number after an
    option read as its value (`--size -1e-3`), so that the value's check answers."""

    # -1, -.5, -1e-3, -inf, -nan, and lists such as -1,2 or -1:1:3: no option starts so
    # (argparse's own takes -1 and -0.5 only)
    _negative_number_matcher = re.compile(r"^-(\.?\d|inf|nan)", re.IGNORECASE)

    def __init__(self, *args, **kwargs):
        kwargs["allow_abbrev"] = False
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = OneLineParser._negative_number_matcher

    def error(self, message):
        self.exit(2, f"{self.prog}: error: {message} (see --help)\n")


def described(doc: str) -> dict:
    """A parser's description (the first paragraph of a module's docstring `doc`) and
    epilogue (the rest of it)."""
    head, _, rest = doc.partition("\n\n")
    return {"description": head, "epilog": rest,
            "formatter_class": argparse.RawDescriptionHelpFormatter}
