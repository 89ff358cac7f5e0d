#version 330 core
// Scene preview (render/scene_preview.h), the key light's shadow map: depth only, drawn with
// scene.vert from the light.

void main() {}
