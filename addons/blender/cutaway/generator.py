"""Running the cutaway executable: `cutaway piece TEMPLATE --cut CUT --seed SEED -o FILE.glb`,
waited for (cut_piece) or in the background (CutJob)."""

import os
import shutil
import subprocess
import tempfile
import time

TIMEOUT_S = 600  # a dense dice of a large template takes a minute or two on two cores


class GeneratorError(RuntimeError):
    """The executable could not be found or run, or failed; the message says why."""


def find_executable(setting):
    """The cutaway executable of the add-on's preferences: a path, or a name on PATH."""
    path = os.path.expanduser(setting or "cutaway")
    if os.sep in path:
        if os.path.isfile(path) and os.access(path, os.X_OK):
            return os.path.abspath(path)
        raise GeneratorError(f"cutaway executable {path} not found or not executable "
                             "(Preferences > Add-ons > Cutaway)")
    found = shutil.which(path)
    if found is None:
        raise GeneratorError(f"no '{path}' on PATH: set the cutaway executable in "
                             "Preferences > Add-ons > Cutaway")
    return found


def templates_dir(setting, executable):
    """The templates folder of the preferences, else templates/ beside the build folder that
    holds the executable (build/cutaway in a source checkout)."""
    if setting:
        return os.path.expanduser(setting)
    return os.path.join(os.path.dirname(os.path.dirname(executable)), "templates")


def template_names(folder):
    """The templates in a folder (names without .yaml), sorted."""
    try:
        files = os.listdir(folder)
    except OSError:
        return []
    return sorted(f[:-len(".yaml")] for f in files if f.endswith(".yaml"))


def resolve_template(template, folder):
    """The template file: a path as given, or a name looked up in the templates folder."""
    path = os.path.expanduser(template)
    if os.sep in template or template.endswith(".yaml"):
        candidates = [path]
    else:
        candidates = [os.path.join(folder, template + ".yaml")]
    for candidate in candidates:
        if os.path.isfile(candidate):
            return os.path.abspath(candidate)
    raise GeneratorError(f"template '{template}' not found (looked for {candidates[0]})")


class CutJob:
    """One `cutaway piece TEMPLATE --cut CUT --seed SEED --apart APART -o FILE.glb` run in the
    background, writing into a private temporary folder: poll() says whether it has ended,
    cancel() stops it, close() stops it and removes the folder. Blender's modal Add > Cut Fruit
    polls one from a timer, so that Blender stays usable while cutaway cuts."""

    def __init__(self, executable, template, cut, seed, apart=0.0):
        self.scratch = tempfile.mkdtemp(prefix="cutaway-")
        self.output = os.path.join(self.scratch, "piece.glb")
        self.started = time.monotonic()
        command = [executable, "piece", template, "--cut", cut, "--seed", str(seed),
                   "--apart", repr(float(apart)), "-q", "-o", self.output]
        self._messages = open(os.path.join(self.scratch, "messages.txt"), "w+")
        try:
            self.process = subprocess.Popen(command, stdin=subprocess.DEVNULL,
                                            stdout=self._messages, stderr=subprocess.STDOUT)
        except OSError as error:
            self.close()
            raise GeneratorError(f"could not run {executable}: {error.strerror}") from None

    def seconds(self):
        """Seconds since the job started."""
        return time.monotonic() - self.started

    def poll(self):
        """True once cutaway has written the file, False while it runs. Raises GeneratorError
        with cutaway's message when it failed, and stops it after TIMEOUT_S."""
        code = self.process.poll()
        if code is None:
            if self.seconds() > TIMEOUT_S:
                self.cancel()
                raise GeneratorError(f"cutaway took more than {TIMEOUT_S} s and was stopped")
            return False
        if code != 0:
            self._messages.seek(0)
            message = self._messages.read().strip() or f"exit status {code}"
            raise GeneratorError(f"cutaway failed: {message}")
        if not os.path.isfile(self.output):
            raise GeneratorError(f"cutaway wrote no {self.output}")
        return True

    def cancel(self):
        """Stops cutaway if it still runs (SIGTERM, then SIGKILL after 5 s): it leaves no
        partial file."""
        if self.process is not None and self.process.poll() is None:
            self.process.terminate()
            try:
                self.process.wait(timeout=5)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()

    def close(self):
        """cancel(), then removes the temporary folder and what it holds."""
        if getattr(self, "process", None) is not None:
            self.cancel()
        self._messages.close()
        shutil.rmtree(self.scratch, ignore_errors=True)


def cut_piece(executable, template, cut, seed, output, apart=0.0):
    """Writes the pieces of `template` cut by `cut` (cutaway's notation, e.g. wedges:4) of the
    variant `seed` to the glTF file `output`, assembled as cut or pulled `apart` (cutaway piece
    --apart), waiting for cutaway (a CutJob). Raises GeneratorError with the executable's
    message when it fails."""
    job = CutJob(executable, template, cut, seed, apart)
    try:
        while not job.poll():
            time.sleep(0.05)
        shutil.copyfile(job.output, output)
    finally:
        job.close()
