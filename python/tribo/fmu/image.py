"""An .fmu file as bytes (`FmuImage`), so that a task on any Dask worker, local or on
another machine, can run it without a shared file system; `unpacked(image)` gives a
private directory with it unpacked, removed afterwards. A file that is not an FMU is
refused when it is loaded, in one line (`FmuError`)."""

import contextlib
import functools
import hashlib
import io
import os
import tempfile
import weakref
import zipfile
from dataclasses import dataclass

from fmpy import read_model_description


class FmuError(ValueError):
    """A file that is not an FMU the package can run (the message, one line, names it)."""


@dataclass(frozen=True)
class FmuImage:
    """The bytes of an .fmu file, its name and their SHA-256."""

    name: str
    data: bytes
    sha256: str

    @classmethod
    def load(cls, path: str) -> "FmuImage":
        """The FMU at `path`: FmuError for a file that is not one (not a zip archive, no
        modelDescription.xml in it, or one fmpy cannot read)."""
        with open(path, "rb") as f:
            data = f.read()
        image = cls(os.path.basename(path), data, hashlib.sha256(data).hexdigest())
        try:
            image.model_description()
        except FmuError as e:
            raise FmuError(f"{path}: {e}") from None
        return image

    def model_description(self):
        """The model description, read from the bytes (cached per FMU)."""
        return _description_of_bytes(self.sha256, self.data)


def _description_of_bytes(sha256: str, data: bytes):
    if sha256 not in _descriptions_by_hash:
        try:
            with zipfile.ZipFile(io.BytesIO(data)) as z, \
                    tempfile.TemporaryDirectory(prefix="tribo_md_") as tmp:
                path = os.path.join(tmp, "modelDescription.xml")
                with open(path, "wb") as f:
                    f.write(z.read("modelDescription.xml"))
                _descriptions_by_hash[sha256] = read_model_description(path, validate=False)
        except zipfile.BadZipFile:
            raise FmuError("not an FMU (not a zip archive)") from None
        except KeyError:
            raise FmuError("not an FMU (no modelDescription.xml in the archive)") from None
        except Exception as e:  # fmpy's reader raises what its XML parser raises
            raise FmuError(f"not an FMU (its modelDescription.xml: "
                           f"{str(e).splitlines()[0] if str(e) else type(e).__name__})") from None
    return _descriptions_by_hash[sha256]


_descriptions_by_hash = {}


@contextlib.contextmanager
def unpacked(image: FmuImage):
    """A private directory holding the FMU unpacked; removed on leaving."""
    with tempfile.TemporaryDirectory(prefix="tribo_fmu_") as tmp:
        with zipfile.ZipFile(io.BytesIO(image.data)) as z:
            z.extractall(tmp)
        yield tmp


def per_description(function):
    """`function(md)` computed once per model description: fmpy's descriptions are read
    once per FMU and never changed, and a run asks for the tables made from them (names,
    charge models) many times, each a walk over the FMU's hundreds of variables. Kept
    while the description lives; a stand-in that cannot be a weak key (a test's
    SimpleNamespace) is computed each time."""
    cache = weakref.WeakKeyDictionary()

    @functools.wraps(function)
    def cached(md):
        try:
            return cache[md]
        except KeyError:
            value = cache[md] = function(md)
            return value
        except TypeError:
            return function(md)

    return cached
