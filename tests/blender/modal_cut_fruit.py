"""Add > Cut Fruit with a window, as a user runs it: Blender under xvfb-run (not -b), the
operator started as the menu starts it once its dialog is confirmed. It must return
RUNNING_MODAL at once and keep Blender's event loop running while cutaway cuts (a timer ticks
meanwhile), then place the tomato's two halves under one root. Then a second cut is started
and Esc pressed (a simulated key press, Blender run with --enable-event-simulate) while
cutaway cuts: nothing is added, no cutaway is left running, and its temporary folder is gone.
Headless Blender (-b) has no window for the modal handler; addon_test.py's cut-fruit case
covers the job it polls.

    xvfb-run -a blender --factory-startup --enable-event-simulate \
        --python tests/blender/modal_cut_fruit.py -- ADDON.zip CUTAWAY SOURCE_DIR OUT_DIR

Writes OUT_DIR/modal.txt ("passed", or why not) and quits; the test script reads it.
"""

import os
import sys
import time

import bpy

ADDON, CUTAWAY, SOURCE, OUT = sys.argv[sys.argv.index("--") + 1:]
state = {"result": None, "started": None, "ticks": 0}


def report(text):
    with open(os.path.join(OUT, "modal.txt"), "w") as stream:
        stream.write(text + "\n")
    bpy.ops.wm.quit_blender()


def start():
    bpy.ops.preferences.addon_install(filepath=os.path.abspath(ADDON), overwrite=True)
    bpy.ops.preferences.addon_enable(module="cutaway")
    prefs = bpy.context.preferences.addons["cutaway"].preferences
    prefs.executable = os.path.abspath(CUTAWAY)
    prefs.templates_dir = os.path.join(os.path.abspath(SOURCE), "templates")
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)
    return cut_fruit("tomato", "halves", 1, then=watch, after=0.05)


def cut_fruit(template, cut, seed, then, after):
    """Starts Add > Cut Fruit as its confirmed dialog does, then `then` in `after` seconds."""
    window = bpy.context.window_manager.windows[0]
    with bpy.context.temp_override(window=window, area=window.screen.areas[0]):
        state["result"] = bpy.ops.object.cutaway_add_cut_fruit(
            'EXEC_DEFAULT', template=template, cut=cut, seed=seed)
    state["started"] = time.monotonic()
    bpy.app.timers.register(then, first_interval=after)
    return None


def watch():
    state["ticks"] += 1
    roots = [o for o in bpy.data.objects if o.parent is None]
    if not roots and time.monotonic() - state["started"] < 120:
        return 0.05
    pieces = [c for r in roots for c in r.children if "template" in c.keys()]
    if state["result"] != {'RUNNING_MODAL'}:
        report(f"the operator returned {state['result']}, not RUNNING_MODAL")
    elif len(roots) != 1 or len(pieces) != 2:
        report(f"roots {[r.name for r in roots]}, {len(pieces)} pieces: want one root, 2 halves")
    elif state["ticks"] < 2:
        report(f"Blender's timers ticked {state['ticks']} times during the cut: it was blocked")
    else:
        bpy.app.timers.register(start_and_escape, first_interval=0.1)
    return None


def cutaway_running():
    """The process ids of cutaway runs of `piece` (read from /proc)."""
    found = []
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            with open(f"/proc/{pid}/cmdline", "rb") as stream:
                words = stream.read().split(b"\0")
        except OSError:
            continue
        if os.path.abspath(CUTAWAY).encode() in words and b"piece" in words:
            found.append(int(pid))
    return found


def start_and_escape():
    return cut_fruit("kiwi", "wedges:8", 2, then=escape, after=0.3)


def escape():
    if not cutaway_running():
        report("the second cut was not running when Esc was to be pressed")
        return None
    state["running"] = cutaway_running()
    bpy.context.window_manager.windows[0].event_simulate(type='ESC', value='PRESS')
    bpy.context.window_manager.windows[0].event_simulate(type='ESC', value='RELEASE')
    bpy.app.timers.register(after_escape, first_interval=1.0)
    return None


def after_escape():
    roots = [o for o in bpy.data.objects if o.parent is None]
    left = [name for name in os.listdir(os.environ.get("TMPDIR", "/tmp"))
            if name.startswith("cutaway-")]
    if state["result"] != {'RUNNING_MODAL'}:
        report(f"the second cut returned {state['result']}, not RUNNING_MODAL")
    elif len(roots) != 1:
        report(f"Esc: roots {[r.name for r in roots]}, want only the first cut's")
    elif set(state["running"]) & set(cutaway_running()):
        report(f"Esc: cutaway {state['running']} still runs")
    elif left:
        report(f"Esc: its temporary folder was left: {left}")
    else:
        report("passed")
    return None


bpy.app.timers.register(start, first_interval=0.5)
