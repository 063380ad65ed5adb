"""Compiling generated OSL inside Blender: the parts that need no bpy.

Cycles' OSL compiler runs in Blender's own process and prints its errors on file
descriptors 1 and 2, not through Python: `CaptureNative` catches them so the add-on's
error report can quote them (`compiler_errors`). `site_packages_with` finds the
folder of Blender's bundled Python that holds `oslquery`, which Cycles' script-node
driver imports and the pip `bpy` wheel keeps off sys.path.
"""

import ctypes
import glob
import os
import sys
import tempfile


class CaptureNative:
    """Captures what native code (the OSL compiler) prints on fds 1 and 2; `text`
    holds it after the with-block. Where the fds cannot be redirected, captures
    nothing and lets the output through."""

    def __enter__(self):
        self.text = ""
        try:
            self._flush()
            self._file = tempfile.TemporaryFile()
            self._saved = [os.dup(1), os.dup(2)]
            os.dup2(self._file.fileno(), 1)
            os.dup2(self._file.fileno(), 2)
        except OSError:
            self._file = None
        return self

    def __exit__(self, *exc):
        if self._file is None:
            return False
        self._flush()
        os.dup2(self._saved[0], 1)
        os.dup2(self._saved[1], 2)
        for fd in self._saved:
            os.close(fd)
        self._file.seek(0)
        self.text = self._file.read().decode("utf-8", "replace")
        self._file.close()
        return False

    @staticmethod
    def _flush():
        sys.stdout.flush()
        sys.stderr.flush()
        try:
            ctypes.CDLL(None).fflush(None)
        except (OSError, AttributeError):
            pass


def compiler_errors(captured, reports):
    """The lines worth quoting when a shader did not compile: what the compiler printed
    that mentions an error, then Cycles' reports other than its success message."""
    words = [line for line in (captured or "").splitlines() if "error" in line.lower()]
    return words + [m for m in reports if m and "succeeded" not in m]


def site_packages_with(root, module):
    """The site-packages folders of a Python installation `root` (lib/python*/site-packages)
    that hold the package `module`, sorted."""
    return [folder for folder in sorted(glob.glob(os.path.join(root, "lib", "python*", "site-packages")))
            if os.path.isdir(os.path.join(folder, module))]
