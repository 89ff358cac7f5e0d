// The DS model in 3D (three.js, served from Debian's libjs-three), turned with the mouse
// (OrbitControls): see-through, the model's glTF as the library exports it (`cutaway model`
// writes the same bytes), every surface drawn translucent and double-sided so that the inner
// surfaces show through the skin; or the outside, the uncut object with its skin baked as
// scenes bake it (patterns, relief), drawn as the file says and lit as scenes are: the file's
// studio lights, sky and exposure, rendered as doc/lighting.md tells a three.js user to, so the
// skin shows the colours it has in the preview, POV-Ray, three.js and Blender.
import * as THREE from 'three';
import { GLTFLoader } from '/lib/three/examples/jsm/loaders/GLTFLoader.js';
import { OrbitControls } from '/lib/three/examples/jsm/controls/OrbitControls.js';

export class ModelView {
  constructor(canvas) {
    this.canvas = canvas;
    // WebGL 2 where the browser has it: textures of any size keep their mipmaps (under WebGL 1,
    // three.js r111 shrinks a baked skin of 1000 x 496 texels to 512 x 256).
    const attributes = { antialias: true, preserveDrawingBuffer: true };
    const context = canvas.getContext('webgl2', attributes) ?? undefined;
    this.renderer = new THREE.WebGLRenderer({ canvas, context, ...attributes });
    this.renderer.setClearColor(0xffffff);
    this.scene = new THREE.Scene();
    // The see-through model's lights: a diagram's, not a scene's.
    this.diagramLights = [new THREE.HemisphereLight(0xffffff, 0x666666, 1.0),
      new THREE.DirectionalLight(0xffffff, 0.6)];
    this.diagramLights[1].position.set(1, 2, 3);
    for (const light of this.diagramLights) this.scene.add(light);
    this.sky = null;  // the outside's sky (a hemisphere light of the file's ambient_lux)
    this.fileCamera = null;  // the outside's camera, as the file gives it
    this.shown = null;  // the glTF bytes on view (ArrayBuffer)
    this.camera = new THREE.PerspectiveCamera(30, 1, 0.001, 100);
    this.controls = new OrbitControls(this.camera, canvas);
    this.controls.addEventListener('change', () => this.render());
    this.model = null;
    new ResizeObserver(() => this.render()).observe(canvas);
  }

  /// Shows the model of glTF bytes `buffer` (ArrayBuffer), see-through unless `outside`,
  /// framing it when `reframe`.
  show(buffer, reframe, outside = false) {
    return new Promise((resolve, reject) => {
      new GLTFLoader().parse(buffer, '', (gltf) => {
        this.shown = buffer;  // the glTF bytes on view
        if (this.model) this.scene.remove(this.model);
        if (this.sky) this.scene.remove(this.sky);
        this.sky = null;
        this.model = gltf.scene;
        this.light(outside ? gltf.scene.userData : null);
        this.fileCamera = outside ? gltf.cameras[0] ?? null : null;
        this.model.traverse((o) => {
          if (!o.isMesh || outside) return;
          const m = o.material;
          m.transparent = true;
          m.opacity = 0.35;
          m.depthWrite = false;
          m.side = THREE.DoubleSide;
        });
        this.scene.add(this.model);
        if (reframe) this.frame();
        this.render();
        resolve();
      }, reject);
    });
  }

  /// Lights the view as a scene (`view`: the file's scene extras, with its exposure and
  /// ambient_lux; its lights are in the model) or, with null, as the see-through diagram.
  light(view) {
    const r = this.renderer;
    for (const light of this.diagramLights) light.visible = !view;
    // Debian's three.js (r111): physically correct lights take a directional light's intensity
    // as lux and a hemisphere light's as the sky's illuminance; linear tone mapping by the
    // exposure; gamma 2.2 out (r111 has no sRGB output for the canvas; its curve is within a
    // few steps of sRGB's). The sky from above, 0.4 of it from below, as in the preview.
    r.physicallyCorrectLights = !!view;
    r.gammaOutput = !!view;
    r.gammaFactor = view ? 2.2 : 2.0;
    r.toneMapping = view ? THREE.LinearToneMapping : THREE.NoToneMapping;
    r.toneMappingExposure = view?.exposure ?? 1;
    if (view) {
      this.sky = new THREE.HemisphereLight(new THREE.Color(1, 1, 1), new THREE.Color(0.4, 0.4, 0.4),
                                           view.ambient_lux ?? 0);
      this.scene.add(this.sky);
    }
  }

  /// Looks at the model as the file's camera does (the outside: the camera scenes and the
  /// preview frame a whole object with), keeping the orbit's target on the model's centre.
  viewFromFile() {
    if (!this.fileCamera || !this.model) return;
    this.fileCamera.updateMatrixWorld(true);
    const from = this.fileCamera.getWorldPosition(new THREE.Vector3());
    const centre = new THREE.Box3().setFromObject(this.model).getCenter(new THREE.Vector3());
    this.camera.fov = this.fileCamera.fov;
    this.camera.position.copy(from);
    this.controls.target.copy(centre);
    this.controls.update();
    this.render();
  }

  frame() {
    const box = new THREE.Box3().setFromObject(this.model);
    const centre = box.getCenter(new THREE.Vector3());
    const size = box.getSize(new THREE.Vector3()).length();
    this.camera.near = size / 100;
    this.camera.far = size * 10;
    this.camera.position.copy(centre).add(new THREE.Vector3(0.6, 0.5, 1).normalize().multiplyScalar(size * 1.9));
    this.controls.target.copy(centre);
    this.controls.update();
  }

  render() {
    const w = this.canvas.clientWidth, h = this.canvas.clientHeight;
    if (!w || !h) return;
    this.renderer.setPixelRatio(window.devicePixelRatio || 1);
    this.renderer.setSize(w, h, false);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.renderer.render(this.scene, this.camera);
  }
}
