// The DS model in 3D (three.js, served from Debian's libjs-three), turned with the mouse
// (OrbitControls): see-through, the model's glTF as the library exports it (`cutaway model`
// writes the same bytes), every surface drawn translucent and double-sided so that the inner
// surfaces show through the skin; or the outside, the uncut object with its skin baked as
// scenes bake it (patterns, relief), drawn as the file says.
import * as THREE from 'three';
import { GLTFLoader } from '/lib/three/examples/jsm/loaders/GLTFLoader.js';
import { OrbitControls } from '/lib/three/examples/jsm/controls/OrbitControls.js';

export class ModelView {
  constructor(canvas) {
    this.canvas = canvas;
    this.renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
    this.renderer.setClearColor(0xffffff);
    this.scene = new THREE.Scene();
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x666666, 1.0));
    const sun = new THREE.DirectionalLight(0xffffff, 0.6);
    sun.position.set(1, 2, 3);
    this.scene.add(sun);
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
        if (this.model) this.scene.remove(this.model);
        this.model = gltf.scene;
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
