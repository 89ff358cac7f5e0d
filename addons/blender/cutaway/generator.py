"""Running the cutaway executable: `cutaway piece TEMPLATE --cut CUT --seed SEED -o FILE.glb`."""

import os
import shutil
import subprocess

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


def cut_piece(executable, template, cut, seed, output, apart=0.0):
    """Writes the pieces of `template` cut by `cut` (cutaway's notation, e.g. wedges:4) of the
    variant `seed` to the glTF file `output`, assembled as cut or pulled `apart` (cutaway piece
    --apart). Raises GeneratorError with the executable's message when it fails."""
    command = [executable, "piece", template, "--cut", cut, "--seed", str(seed),
               "--apart", repr(float(apart)), "-o", output]
    try:
        done = subprocess.run(command, capture_output=True, text=True, timeout=TIMEOUT_S,
                              check=False)
    except OSError as error:
        raise GeneratorError(f"could not run {executable}: {error.strerror}") from None
    except subprocess.TimeoutExpired:
        raise GeneratorError(f"cutaway took more than {TIMEOUT_S} s and was stopped") from None
    if done.returncode != 0:
        message = done.stderr.strip() or done.stdout.strip() or f"exit status {done.returncode}"
        raise GeneratorError(f"cutaway failed: {message}")
    if not os.path.isfile(output):
        raise GeneratorError(f"cutaway wrote no {output}")
