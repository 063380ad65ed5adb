"""Running POV-Ray on facet's scenes: a linear 16-bit PNG, exact with one run per pass.

`render` takes the scene's `pov.Plan`, which facet gave when it wrote the scene
(`pov.generate_scene`, i.e. `facet generate --target pov --json`); the number of runs
is never read back from the .pov. A .pov that did not come from `generate_scene`
(written by hand or by another tool) has no Plan, and `render` refuses it with a
message that says so: the add-on renders only the scenes it has just generated.

Every run is `povray +I<scene> +O<image> +W +H +FP16 File_Gamma=1.0 -D -P +V` plus
the `Settings` (anti-aliasing, quality; EXACT by default: -A +Q9) in the scene's folder
(POV-Ray's I/O restrictions allow it), in a process group of its own, its output in a
log file; passes run as many at a time as there are processors. A `Job` runs them while
its caller polls (the render engine, which can cancel); `render` waits for one. On a
failure or a cancel the other runs are killed, the message names the pass and POV-Ray's
last lines, and neither the PNG nor a temporary file is left.
"""

import os
import re
import shutil
import signal
import subprocess
import tempfile
import time
from dataclasses import dataclass

from . import UserError, cli, pov

# facet's scenes declare this near their top; `Declare=Facet_Exposure=x` scales radiance.
EXPOSURE_DECLARATION = "Facet_Exposure"
PREFERENCES_HINT = "Edit > Preferences > Add-ons > facet > POV-Ray executable"
HEADER_BYTES = 65536
TIMEOUT = 3600                 # seconds for one run
POLL_SECONDS = 0.05


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


@dataclass(frozen=True)
class Settings:
    """POV-Ray's anti-aliasing and quality. The default is the exact mode: no
    anti-aliasing (one ray through each pixel centre, as facet's reference samples it)
    at full quality; `facet validate` and Export POV-Ray render that way."""
    antialias: bool = False
    threshold: float = 0.3       # +A<threshold>: supersample where neighbours differ by more
    depth: int = 3               # +R<depth>: recursion depth (method 2) / grid (method 1)
    method: int = 2              # +AM1 non-recursive, +AM2 adaptive
    quality: int = 9             # +Q<quality>: 9 is POV-Ray's full quality

    def options(self):
        aa = ([f"+A{self.threshold:g}", f"+AM{self.method}", f"+R{self.depth}"] if self.antialias else ["-A"])
        return aa + [f"+Q{self.quality}"]


EXACT = Settings()
PROGRESS = re.compile(r"Rendered (\d+) of (\d+) pixels")


class _Run:
    """One POV-Ray run in the scene's folder, in a process group of its own (a stand-in
    script's children stop with it), its output in a log file beside its image."""

    def __init__(self, povray, folder, pov_name, out_rel, width, height, options, what):
        self.out = os.path.join(folder, out_rel)
        self.log_path = os.path.splitext(self.out)[0] + ".log"
        self.what, self.started = what, time.monotonic()
        self.reported = 0.0   # the most this run has said it rendered (fraction never goes back)
        # POV-Ray's I/O restrictions allow the working folder: run it there with plain names.
        command = [povray, "+I" + pov_name, "+O" + out_rel, f"+W{width}", f"+H{height}", "+FP16",
                   "File_Gamma=1.0", "-D", "-P", "+V"] + options
        with open(self.log_path, "wb") as log:
            try:
                self.proc = subprocess.Popen(command, cwd=folder, stdin=subprocess.DEVNULL, stdout=log,
                                             stderr=subprocess.STDOUT, start_new_session=True)
            except OSError as e:
                raise UserError(f"cannot run POV-Ray '{povray}': {e}")

    def _tail(self, size=8192):
        with open(self.log_path, "rb") as f:
            f.seek(max(0, os.path.getsize(self.log_path) - size))
            return f.read().decode("utf-8", "replace")

    def fraction(self):
        """How much of the image POV-Ray says it has rendered (its +V progress lines), never less
        than it said before: once the render ends, its statistics push the last progress line out
        of the log's tail before the process exits."""
        if self.proc.poll() is not None:
            return 1.0
        found = PROGRESS.findall(self._tail(512))
        if found:
            self.reported = max(self.reported, int(found[-1][0]) / max(1, int(found[-1][1])))
        return self.reported

    def done(self):
        """True once POV-Ray has written the image; a UserError with its last lines when
        it failed or ran past TIMEOUT (the caller stops the other runs)."""
        code = self.proc.poll()
        if code is None:
            if time.monotonic() - self.started > TIMEOUT:
                self.stop()
                raise UserError(f"POV-Ray took more than an hour ({self.what}); stopped")
            return False
        if code != 0 or not os.path.exists(self.out) or os.path.getsize(self.out) == 0:
            why = f"exit status {code}" if code != 0 else "it wrote no image"
            lines = [l for l in re.split(r"[\r\n]+", self._tail()) if l.strip() and not PROGRESS.search(l)][-8:]
            raise UserError(f"POV-Ray failed ({self.what}; {why}):\n" + "\n".join(lines))
        return True

    def stop(self):
        """Kills the run's whole process group and waits for POV-Ray."""
        if self.proc.poll() is None:
            try:
                os.killpg(self.proc.pid, signal.SIGKILL)
            except OSError:                          # already gone
                pass
        self.proc.wait()


class Job:
    """A render of facet's POV-Ray scene that runs while the caller polls it (Blender's
    render engine checks Esc between polls; `render` below waits for it).

    The runs (one per pass of the scene's pov.Plan, Declare=Facet_Light=i, as many at a
    time as there are processors; one plain run for passes 1) write 16-bit PPMs into a
    temporary folder beside the scene. `poll()` starts the next runs, says whether all
    are done and raises a UserError when one failed; `image()` adds the passes up;
    `close()` (also on leaving a `with` block) kills what still runs, each run's whole
    process group, and removes the temporary folder."""

    def __init__(self, povray, pov_path, plan, width, height, exposure=1.0, settings=EXACT):
        if not isinstance(plan, pov.Plan):
            raise UserError(f"{pov_path}: facet did not say how many POV-Ray runs make this scene's image "
                            f"(facet generate --json); the add-on renders only the POV-Ray scenes it has just "
                            f"exported")
        if exposure != 1.0:
            check_exposure_hook(pov_path)
        self.povray, self.pov_path, self.plan = povray, pov_path, plan
        self.width, self.height = width, height
        self.options = settings.options() + ([f"Declare={EXPOSURE_DECLARATION}={exposure!r}"]
                                             if exposure != 1.0 else [])
        self.folder = os.path.dirname(os.path.abspath(pov_path))
        self.tmp = tempfile.mkdtemp(prefix=".facet-pov-", dir=self.folder)
        self.waiting, self.running, self.finished = list(range(plan.passes)), [], []
        self.at_once = max(1, os.cpu_count() or 1)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def _run(self, i):
        count = self.plan.passes
        name = f"pass{i}.ppm" if count > 1 else "render.ppm"
        light = [f"Declare=Facet_Light={i}"] if count > 1 else []
        return _Run(self.povray, self.folder, os.path.basename(self.pov_path),
                    os.path.join(os.path.basename(self.tmp), name), self.width, self.height,
                    light + self.options, f"pass {i + 1} of {count}" if count > 1 else "one run")

    def poll(self):
        """Starts what may start; True when every run has finished (UserError on a failure)."""
        for run in [r for r in self.running if r.done()]:
            self.running.remove(run)
            self.finished.append(run)
        while self.waiting and len(self.running) < self.at_once:
            self.running.append(self._run(self.waiting.pop(0)))
        return not self.waiting and not self.running

    def progress(self):
        """0..1: the finished runs and what the running ones say they have rendered."""
        return (len(self.finished) + sum(r.fraction() for r in self.running)) / self.plan.passes

    def image(self):
        """(width, height, samples): the passes added and clipped at 65535 (1.0), 16-bit
        RGB as an array('H'), top row first. After poll() returned True."""
        images = [pov.read_ppm16(run.out) for run in sorted(self.finished, key=lambda r: r.out)]
        if any(img[:2] != (self.width, self.height) for img in images):
            raise UserError(f"POV-Ray wrote images of another size than {self.width}x{self.height}")
        return self.width, self.height, pov.add_clipped([img[2] for img in images])

    def close(self):
        for run in self.running:
            run.stop()
        self.running = []
        shutil.rmtree(self.tmp, ignore_errors=True)


def render(povray, pov_path, plan, png_path, width, height, exposure=1.0, settings=EXACT):
    """Renders `pov_path` to `png_path` (linear 16-bit PNG, whole or not at all); the PNG
    holds radiance × `exposure` (facet's scenes declare Facet_Exposure for that).

    `plan` is the scene's pov.Plan from facet (pov.generate_scene). With plan.passes > 1
    the scene is rendered the exact way: one run per pass (Declare=Facet_Light=i), as
    many at a time as there are processors, each a 16-bit PPM, added up. `settings`:
    anti-aliasing and quality (EXACT: none, full). Returns the number of runs."""
    with Job(povray, pov_path, plan, width, height, exposure, settings) as job:
        while not job.poll():
            time.sleep(POLL_SECONDS)
        cli.write_atomic(png_path, pov.png16(*job.image()))
    return plan.passes
