"""Add > Cut Fruit with a window, as a user runs it: Blender under xvfb-run (not -b), the
operator started as the menu starts it once its dialog is confirmed. It must return
RUNNING_MODAL at once and keep Blender's event loop running while cutaway cuts (a timer ticks
meanwhile), then place the tomato's two halves under one root. Headless Blender (-b) has no
window for the modal handler; addon_test.py's cut-fruit case covers the job it polls.

    xvfb-run -a blender --factory-startup --python tests/blender/modal_cut_fruit.py -- \
        ADDON.zip CUTAWAY SOURCE_DIR OUT_DIR

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
    window = bpy.context.window_manager.windows[0]
    with bpy.context.temp_override(window=window, area=window.screen.areas[0]):
        state["result"] = bpy.ops.object.cutaway_add_cut_fruit(
            'EXEC_DEFAULT', template="tomato", cut="halves", seed=1)
    state["started"] = time.monotonic()
    bpy.app.timers.register(watch, first_interval=0.05)
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
        report("passed")
    return None


bpy.app.timers.register(start, first_interval=0.5)
