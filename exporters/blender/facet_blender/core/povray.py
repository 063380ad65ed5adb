"""Running POV-Ray on facet's scenes: a linear 16-bit PNG, exact with one run per pass.

`render` takes the scene's `pov.Plan`, which facet gave when it wrote the scene
(`pov.generate_scene`, i.e. `facet generate --target pov --json`); the number of runs
is never read back from the .pov. A .pov that did not come from `generate_scene`
(written by hand or by another tool) has no Plan, and `render` refuses it with a
message that says so: the add-on renders only the scenes it has just generated.

Every run is `povray +I<scene> +O<image> +W +H -A File_Gamma=1.0 -D -P -V` in the
scene's folder (POV-Ray's I/O restrictions allow it); passes run as many at a time as
there are processors. On a failure the other runs are stopped, the message names the
pass and POV-Ray's last lines, and neither the PNG nor a temporary file is left.
"""

import os
import shutil
import subprocess
import tempfile

from . import UserError, cli, pov

# facet's scenes declare this near their top; `Declare=Facet_Exposure=x` scales radiance.
EXPOSURE_DECLARATION = "Facet_Exposure"
PREFERENCES_HINT = "Edit > Preferences > Add-ons > facet > POV-Ray executable"
HEADER_BYTES = 65536
TIMEOUT = 3600                 # seconds for one run


def default_povray_path():
    """The preference's default: povray on PATH, else ''."""
    return shutil.which("povray") or ""


def find_povray(preferred=""):
    """The POV-Ray executable: `preferred` (a path or a command name), else povray on PATH."""
    path = preferred or default_povray_path()
    found = shutil.which(path) if path else None
    if not found:
        raise UserError(f"POV-Ray not found{f' at {path!r}' if path else ''}: install POV-Ray 3.7 or set "
                        f"its path in {PREFERENCES_HINT}")
    return found


def _read_header(path):
    with open(path, encoding="utf-8", errors="replace") as f:
        return f.read(HEADER_BYTES)


def check_exposure_hook(pov_path):
    """facet's POV-Ray scenes declare Facet_Exposure near their top; make sure this one does."""
    if EXPOSURE_DECLARATION not in _read_header(pov_path):
        raise UserError(f"{pov_path} does not declare {EXPOSURE_DECLARATION} (an older facet?): "
                        f"render with Exposure 1")


def _start(povray, folder, pov_name, out_name, width, height, options):
    """One POV-Ray run in `folder`; returns the Popen (output in its .communicate())."""
    # POV-Ray's I/O restrictions allow the working folder: run it there with plain names.
    command = [povray, "+I" + pov_name, "+O" + out_name, f"+W{width}", f"+H{height}", "-A",
               "File_Gamma=1.0", "-D", "-P", "-V"] + options
    try:
        return subprocess.Popen(command, cwd=folder, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                text=True, errors="replace")
    except OSError as e:
        raise UserError(f"cannot run POV-Ray '{povray}': {e}")


def _finish(proc, out_path, what):
    """Waits for a run; a UserError with POV-Ray's last lines unless it wrote `out_path`."""
    try:
        stdout, stderr = proc.communicate(timeout=TIMEOUT)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.communicate()
        raise UserError(f"POV-Ray took more than an hour ({what}); stopped")
    if proc.returncode != 0 or not os.path.exists(out_path) or os.path.getsize(out_path) == 0:
        why = f"exit status {proc.returncode}" if proc.returncode != 0 else "it wrote no image"
        lines = [l for l in (stderr + stdout).splitlines() if l.strip()][-8:]
        raise UserError(f"POV-Ray failed ({what}; {why}):\n" + "\n".join(lines))


def render(povray, pov_path, plan, png_path, width, height, exposure=1.0):
    """Renders `pov_path` to `png_path` (linear 16-bit PNG, whole or not at all); the PNG
    holds radiance × `exposure` (facet's scenes declare Facet_Exposure for that).

    `plan` is the scene's pov.Plan from facet (pov.generate_scene). With plan.passes > 1
    the scene is rendered the exact way: one run per pass (Declare=Facet_Light=i), as
    many at a time as there are processors, each a 16-bit PPM, added up. Returns the
    number of runs."""
    if not isinstance(plan, pov.Plan):
        raise UserError(f"{pov_path}: facet did not say how many POV-Ray runs make this scene's image "
                        f"(facet generate --json); the add-on renders only the POV-Ray scenes it has just "
                        f"exported")
    if exposure != 1.0:
        check_exposure_hook(pov_path)
    folder = os.path.dirname(os.path.abspath(pov_path))
    count = plan.passes
    options = [f"Declare={EXPOSURE_DECLARATION}={exposure!r}"] if exposure != 1.0 else []
    with tempfile.TemporaryDirectory(prefix=".facet-pov-", dir=folder) as tmp:
        name = os.path.basename(tmp)
        if count == 1:
            out = os.path.join(tmp, "render.png")
            _finish(_start(povray, folder, os.path.basename(pov_path), os.path.join(name, "render.png"),
                           width, height, ["+FN16"] + options), out, "one run")
            result = out
        else:
            outs = [os.path.join(tmp, f"pass{i}.ppm") for i in range(count)]
            running, at_once = [], max(1, os.cpu_count() or 1)
            try:
                for i in range(count):
                    if len(running) >= at_once:
                        _finish(*running.pop(0))
                    running.append((_start(povray, folder, os.path.basename(pov_path),
                                           os.path.join(name, f"pass{i}.ppm"), width, height,
                                           ["+FP16", f"Declare=Facet_Light={i}"] + options),
                                    outs[i], f"pass {i + 1} of {count}"))
                while running:
                    _finish(*running.pop(0))
            finally:
                for proc, _, _ in running:          # after a failure: stop the others
                    proc.kill()
                    proc.communicate()
            images = [pov.read_ppm16(path) for path in outs]
            if any(img[:2] != (width, height) for img in images):
                raise UserError(f"POV-Ray wrote images of another size than {width}x{height}")
            result = os.path.join(tmp, "sum.png")
            with open(result, "wb") as f:
                f.write(pov.png16(width, height, pov.add_clipped([img[2] for img in images])))
        with open(result, "rb") as f:
            cli.write_atomic(png_path, f.read())
    return count
