# Loads one imported scene (res:// path in CUTAWAY_SCENE) in Godot 3 and prints what a game gets
# from it, as one line "CUTAWAY_RESULT <json>": per body its kind, its collision shapes' classes,
# and its mesh's local bounding box (millimetres) and whether a material has a texture.
# Run by import_test.sh after the editor has imported the files.
extends SceneTree

func mm(v):
	return [v.x * 1000, v.y * 1000, v.z * 1000]

func walk(node, out):
	if node is PhysicsBody:
		var body = {"name": node.name, "kind": node.get_class(), "shapes": [],
			"aabb_mm": null, "textured": false}
		for c in node.get_children():
			if c is CollisionShape and c.shape != null:
				body["shapes"].append(c.shape.get_class())
			if c is MeshInstance and c.mesh != null:
				var box = c.mesh.get_aabb()
				body["aabb_mm"] = [mm(box.position), mm(box.size)]
				for k in range(c.mesh.get_surface_count()):
					var m = c.mesh.surface_get_material(k)
					if m is SpatialMaterial and m.albedo_texture != null:
						body["textured"] = true
		out.append(body)
	for c in node.get_children():
		walk(c, out)

func _init():
	var packed = load(OS.get_environment("CUTAWAY_SCENE"))
	if packed == null:
		print("CUTAWAY_RESULT null")
		quit(1)
		return
	var root = packed.instance()
	var out = []
	walk(root, out)
	print("CUTAWAY_RESULT " + to_json(out))
	root.free()
	quit()
