"""An .fmu file as bytes (`FmuImage`), so that a task on any Dask worker, local or on
another machine, can run it without a shared file system; `unpacked(image)` gives a
private directory with it unpacked, removed afterwards."""

import contextlib
import hashlib
import io
import os
import tempfile
import zipfile
from dataclasses import dataclass

from fmpy import read_model_description


@dataclass(frozen=True)
class FmuImage:
    """The bytes of an .fmu file, its name and their SHA-256."""

    name: str
    data: bytes
    sha256: str

    @classmethod
    def load(cls, path: str) -> "FmuImage":
        with open(path, "rb") as f:
            data = f.read()
        return cls(os.path.basename(path), data, hashlib.sha256(data).hexdigest())

    def model_description(self):
        """The model description, read from the bytes (cached per FMU)."""
        return _description_of_bytes(self.sha256, self.data)


def _description_of_bytes(sha256: str, data: bytes):
    if sha256 not in _descriptions_by_hash:
        with zipfile.ZipFile(io.BytesIO(data)) as z, \
                tempfile.TemporaryDirectory(prefix="tribo_md_") as tmp:
            path = os.path.join(tmp, "modelDescription.xml")
            with open(path, "wb") as f:
                f.write(z.read("modelDescription.xml"))
            _descriptions_by_hash[sha256] = read_model_description(path, validate=False)
    return _descriptions_by_hash[sha256]


_descriptions_by_hash = {}


@contextlib.contextmanager
def unpacked(image: FmuImage):
    """A private directory holding the FMU unpacked; removed on leaving."""
    with tempfile.TemporaryDirectory(prefix="tribo_fmu_") as tmp:
        with zipfile.ZipFile(io.BytesIO(image.data)) as z:
            z.extractall(tmp)
        yield tmp
