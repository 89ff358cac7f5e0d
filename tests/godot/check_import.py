"""Checks what Godot made of one cutaway glTF file (the JSON line inspect.gd prints): one
RigidBody per piece, each with convex shapes only, a textured mesh of millimetre size whose
local bounding box holds the body's origin (the piece turns about a point inside it, its centre
of mass), and no StaticBody. Usage: check_import.py RESULT_LINE PIECES"""
import json
import sys

line, pieces = sys.argv[1], int(sys.argv[2])
bodies = json.loads(line.split(" ", 1)[1])
errors = []
if bodies is None:
    errors.append("the scene did not load")
    bodies = []
rigid = [b for b in bodies if b["kind"] == "RigidBody"]
if len(rigid) != pieces:
    errors.append(f"{len(rigid)} RigidBodies, want {pieces}")
for b in bodies:
    if b["kind"] != "RigidBody":
        errors.append(f"{b['name']}: a {b['kind']}, not a RigidBody")
for b in rigid:
    name = b["name"]
    if not b["shapes"] or any(s != "ConvexPolygonShape" for s in b["shapes"]):
        errors.append(f"{name}: shapes {b['shapes']}, want convex ones")
    if not b["textured"]:
        errors.append(f"{name}: no texture")
    if b["aabb_mm"] is None:
        errors.append(f"{name}: no mesh")
        continue
    low, size = b["aabb_mm"]
    if not (5 <= max(size) <= 200 and min(size) >= 0.5):
        errors.append(f"{name}: {size} mm across, not a piece of fruit")
    if not all(low[k] <= 0 <= low[k] + size[k] for k in range(3)):
        errors.append(f"{name}: its origin lies outside its mesh's box {low} + {size} mm")
    print(f"{name}: {len(b['shapes'])} convex shape(s), "
          f"{' x '.join(f'{s:.1f}' for s in size)} mm, textured")
for e in errors:
    print("error:", e, file=sys.stderr)
sys.exit(1 if errors else 0)
