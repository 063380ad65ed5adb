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


# What the add-on says about the shader, in the Text beside facet's own header. Kept in
# step with the README's "What the OSL shader cannot receive".
LIMITS = """\
What this shader cannot receive, and why: it evaluates facet's model analytically for
the lights above and returns the result as emission (an emission closure, no BSDF
closure), so Cycles' path tracer has nothing to scatter on this surface:
  - indirect light: light bounced off other surfaces, and emissive objects (a mesh with
    an Emission shader is not one of the scene's lights), never reach it;
  - the World beyond the ambient term: the World enters only as facet's ambient term,
    the material's ambient colour × the World's colour × strength (a plain Background,
    else 0) as it was at generation, the same from every direction and never occluded;
    an HDRI, a sky texture or the World seen through a window does not light it;
  - area lights (skipped), a light's radius or a sun's angle (treated as points and
    parallel beams), a spot's blend (the cone edge is hard).
Shadows come from trace() towards each light: Cycles on the CPU with Open Shading
Language on."""


def addon_header(light_names, driven):
    """The add-on's comment block for a generated shader lit by `light_names` (in the
    shader's order); `driven` those whose inputs follow their light object."""
    lines = ["", "Blender add-on (facet Generate OSL):"]
    if light_names:
        lines.append("The Script node's inputs light<i>_color, _position, _direction and _cutoff are")
        lines.append("driven by the light objects, so moving, rotating, recolouring or dimming a light")
        lines.append("needs no regeneration; adding, removing or retyping one does (the facet panel")
        lines.append("says when). Lights, in input order:")
        for k, name in enumerate(light_names):
            how = "driven" if name in driven else "fixed as generated (an instance)"
            lines.append(f"  light{k}: '{name}', {how}")
    else:
        lines.append("The scene had no lights facet takes when this was generated.")
    lines.append("")
    lines += LIMITS.splitlines()
    return "\n".join("//" + (" " + line if line else "") for line in lines) + "\n"


def with_addon_header(text, header):
    """`text` with `header` after facet's leading comment block (its first blank line)."""
    head, sep, rest = text.partition("\n\n")
    if not sep:
        return header + text
    return head + "\n" + header + "\n" + rest
