// The cutting view (cut.html): a fruit's whole-object glTF cut by a plane, the cut face (the
// cap) painted live from the interior volume that `cutaway volume` writes. The half of the
// model on the far side of the plane is clipped away; the cap is one quad lying in the plane
// whose fragment shader reads the volume by the sidecar's reading rule (region scores from the
// eight voxels around a point, then the trilinear blend of the winning region's colours).
// Query parameters: volume (URL of the sidecar JSON; its image names are relative to it) and
// model (URL of the .glb). Served by `cutaway edit`, which samples the volume when asked, the
// files are asked for with POST and the server's token; from a plain file server, with GET.
// Test hooks are on window.cutting (see the end of this file).
import * as THREE from 'three';
import { GLTFLoader } from '/lib/three/examples/jsm/loaders/GLTFLoader.js';
import { OrbitControls } from '/lib/three/examples/jsm/controls/OrbitControls.js';
import { decodePng } from './png_decode.js';
import { ask, token } from './server_request.js';

/// How the page asks for the files it loads (ask()'s init).
const asking = token ? { method: 'POST' } : {};

// ---------------------------------------------------------------------------------------------
// The volume: flipbook PNGs unpacked into 3D arrays, and the reading rule on the CPU.

/// The RGBA bytes of the PNG at `url`, exactly as stored (png_decode.js).
async function readPng(url) {
  const response = await ask(url, asking);
  if (!response.ok) throw new Error(`${url}: HTTP ${response.status}`);
  const inflate = async (bytes) => new Uint8Array(await new Response(
    new Blob([bytes]).stream().pipeThrough(new DecompressionStream('deflate'))).arrayBuffer());
  return decodePng(new Uint8Array(await response.arrayBuffer()), inflate);
}

/// The voxels of a flipbook image as one array, x fastest, then y, then z (4 bytes a voxel),
/// which is also the layout a 3D texture takes.
function unpackFlipbook(image, tiling, size) {
  const [nx, ny, nz] = size;
  const { columns, tile_width: tw, tile_height: th } = tiling;
  if (tw !== nx || th !== ny || (tiling.slices ?? nz) !== nz) {
    throw new Error('the tiling does not match the grid size');
  }
  if (image.width < columns * tw || image.height < Math.ceil(nz / columns) * th) {
    throw new Error(`a ${image.width} x ${image.height} image is too small for its tiling`);
  }
  const out = new Uint8Array(nx * ny * nz * 4);
  for (let k = 0; k < nz; ++k) {
    const column = k % columns, row = Math.floor(k / columns);
    for (let j = 0; j < ny; ++j) {
      const y = row * th + (th - 1 - j);
      const from = (y * image.width + column * tw) * 4;
      out.set(image.data.subarray(from, from + nx * 4), ((k * ny + j) * nx) * 4);
    }
  }
  return out;
}

/// FNV-1a (32 bits) of the bytes of a flipbook.
function digest(data) {
  let h = 0x811c9dc5;
  for (let i = 0; i < data.length; ++i) h = Math.imul(h ^ data[i], 0x01000193) >>> 0;
  return h.toString(16).padStart(8, '0');
}

const srgbToLinear = (c) => (c <= 0.04045 ? c / 12.92 : Math.pow((c + 0.055) / 1.055, 2.4));
const linearToSrgb = (c) => (c <= 0.0031308 ? c * 12.92 : 1.055 * Math.pow(c, 1 / 2.4) - 0.055);
const LINEAR = Array.from({ length: 256 }, (_, i) => srgbToLinear(i / 255));

const f32 = new Float32Array(1), u32 = new Uint32Array(f32.buffer);

/// The half float nearest to `value` (finite, not huge; ties round up), as its bits.
function toHalf(value) {
  f32[0] = value;
  const x = u32[0], sign = (x >>> 16) & 0x8000, exp = ((x >>> 23) & 0xff) - 112;
  const mantissa = x & 0x7fffff;
  if (exp >= 31) return sign | 0x7c00;
  if (exp <= 0) {   // subnormal
    if (exp < -10) return sign;
    const full = mantissa | 0x800000, shift = 14 - exp;
    return sign | ((full >> shift) + ((full >> (shift - 1)) & 1));
  }
  return (sign | (exp << 10) | (mantissa >> 13)) + ((mantissa >> 12) & 1);
}

/// Loads the sidecar at `url` and its images. Returns {meta, size, first, voxel, colour,
/// structure, material (RGBA bytes, x fastest), linear (the colour in linear RGB, half floats),
/// digests, solid (Float32Array of solid voxel centres), box (of the solid voxels), reach
/// (the box outside which every point reads as empty)}.
export async function loadVolume(url) {
  const absolute = new URL(url, location.href);
  const response = await ask(absolute, asking);
  if (!response.ok) throw new Error(`${url}: HTTP ${response.status}`);
  const meta = await response.json();
  const size = meta.grid.size, first = meta.grid.first_centre_m, voxel = meta.grid.voxel_m;
  if (size.some((n) => n < 2)) throw new Error('the volume needs two voxels on every axis');
  const names = ['colour', 'structure', 'material'];
  const images = await Promise.all(names.map((n) => readPng(new URL(meta.images[n], absolute))));
  const volume = { meta, size, first, voxel, digests: {} };
  names.forEach((n, i) => {
    volume[n] = unpackFlipbook(images[i], meta.tiling, size);
    volume.digests[n] = digest(images[i].data);
  });
  // Solid voxels: their centres (for choosing which side a knife cut keeps) and their box.
  const [nx, ny, nz] = size;
  const centres = [];
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (let k = 0, v = 0; k < nz; ++k) {
    for (let j = 0; j < ny; ++j) {
      for (let i = 0; i < nx; ++i, ++v) {
        const s = volume.structure;
        if (s[v * 4] === 0 && s[v * 4 + 1] === 0) continue;
        const p = [first[0] + voxel * i, first[1] + voxel * j, first[2] + voxel * k];
        centres.push(...p);
        for (let a = 0; a < 3; ++a) {
          lo[a] = Math.min(lo[a], p[a]);
          hi[a] = Math.max(hi[a], p[a]);
        }
      }
    }
  }
  if (!centres.length) throw new Error('the volume has no solid voxel');
  volume.solid = Float32Array.from(centres);
  volume.box = { min: lo.map((x) => x - voxel / 2), max: hi.map((x) => x + voxel / 2) };
  // Where the reading can give a region at all: within a voxel of a solid one, and in the grid.
  volume.reach = {
    min: lo.map((x, a) => Math.max(x - voxel, first[a])),
    max: hi.map((x, a) => Math.min(x + voxel, first[a] + voxel * (size[a] - 1))),
  };
  // The colour decoded to linear, as half floats: the shader blends it without decoding.
  const half = LINEAR.map(toHalf);
  const alpha = Array.from({ length: 256 }, (_, i) => toHalf(i / 255));
  volume.linear = new Uint16Array(volume.colour.length);
  volume.colour.forEach((byte, i) => {
    volume.linear[i] = ((i & 3) === 3 ? alpha : half)[byte];
  });
  // The stones (rigid surfaces) beside the voxels: meshes in metres, colours decoded to linear.
  volume.stones = (meta.stones ?? []).map((s) => ({
    surface: s.surface,
    points: Float32Array.from(s.points_um, (v) => v * 1e-6),
    triangles: Uint32Array.from(s.triangles),
    stone: Float32Array.from(s.stone_srgb, (b) => LINEAR[b]),
    flesh: Float32Array.from(s.flesh_srgb, (b) => LINEAR[b]),
  }));
  return volume;
}

/// The mean of flat [x, y, z, ...] points.
function meanPoint(points) {
  const n = points.length / 3;
  const g = [0, 0, 0];
  for (let v = 0; v < n; ++v) for (let a = 0; a < 3; ++a) g[a] += points[3 * v + a] / n;
  return g;
}

/// The share of a closed mesh's volume (`points`, `triangles`: a stone; `g`: meanPoint of its
/// points) on the kept side of the plane through `point` with unit `normal`
/// ((p - point) . normal <= 0): each triangle's tetrahedron with `g` counted by the side its
/// centroid lies on.
export function keptShare(points, triangles, g, point, normal) {
  let kept = 0, total = 0;
  for (let t = 0; t < triangles.length; t += 3) {
    const [a, b, c] = [0, 1, 2].map((k) =>
      [0, 1, 2].map((x) => points[3 * triangles[t + k] + x] - g[x]));
    const volume = (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                    a[2] * (b[0] * c[1] - b[1] * c[0])) / 6;
    const side = [0, 1, 2].reduce((sum, x) =>
      sum + ((a[x] + b[x] + c[x]) / 4 + g[x] - point[x]) * normal[x], 0);
    total += volume;
    if (side <= 0) kept += volume;
  }
  return total !== 0 ? kept / total : 0;
}


/// The reading rule at the point (x, y, z) (metres, object frame): {region, rgb} with rgb the
/// sRGB colour in 0..255 (null where the region is 0, empty).
export function readVolume(volume, x, y, z) {
  const { size, first, voxel, structure, colour } = volume;
  const p = [x, y, z], base = [0, 0, 0], f = [0, 0, 0];
  for (let a = 0; a < 3; ++a) {
    const g = (p[a] - first[a]) / voxel;
    if (!(g >= 0 && g <= size[a] - 1)) return { region: 0, rgb: null };
    base[a] = Math.min(Math.floor(g), size[a] - 2);
    f[a] = g - base[a];
  }
  const [nx, ny] = size;
  const index = [], region = [], dist = [], edge = [], weight = [];
  for (let c = 0; c < 8; ++c) {
    const o = [c & 1, (c >> 1) & 1, (c >> 2) & 1];
    const v = ((base[2] + o[2]) * ny + (base[1] + o[1])) * nx + (base[0] + o[0]);
    index.push(v);
    region.push(structure[v * 4] + 256 * structure[v * 4 + 1]);
    dist.push(structure[v * 4 + 2] / 255);
    edge.push(structure[v * 4 + 3] / 255);
    weight.push((o[0] ? f[0] : 1 - f[0]) * (o[1] ? f[1] : 1 - f[1]) * (o[2] ? f[2] : 1 - f[2]));
  }
  // Solid or empty first: the interpolated signed distance to the outline.
  let outline = 0;
  for (let c = 0; c < 8; ++c) outline += weight[c] * (region[c] === 0 ? -edge[c] : edge[c]);
  if (outline <= 0) return { region: 0, rgb: null };
  let best = 0, bestScore = -Infinity;
  for (let c = 0; c < 8; ++c) {
    const r = region[c];
    if (r === 0) continue;
    let score = 0;
    for (let e = 0; e < 8; ++e) score += weight[e] * (region[e] === r ? dist[e] : -dist[e]);
    if (score > bestScore || (score === bestScore && r < best)) { best = r; bestScore = score; }
  }
  if (best === 0) return { region: 0, rgb: null };
  const sum = [0, 0, 0], plain = [0, 0, 0];
  let wsum = 0, n = 0;
  for (let c = 0; c < 8; ++c) {
    if (region[c] !== best) continue;
    for (let a = 0; a < 3; ++a) {
      const lin = LINEAR[colour[index[c] * 4 + a]];
      sum[a] += weight[c] * lin;
      plain[a] += lin;
    }
    wsum += weight[c];
    ++n;
  }
  const rgb = sum.map((s, a) => {
    const lin = wsum > 0 ? s / wsum : plain[a] / n;
    return Math.round(255 * Math.min(1, Math.max(0, linearToSrgb(lin))));
  });
  return { region: best, rgb };
}

// ---------------------------------------------------------------------------------------------
// The cap's shaders: the same rule on the GPU, unlit, written out as sRGB.

const CAP_VERTEX = `
varying vec3 vWorld;
void main() {
  vec4 world = modelMatrix * vec4(position, 1.0);
  vWorld = world.xyz;
  gl_Position = projectionMatrix * viewMatrix * world;
}`;

const CAP_FRAGMENT = `
precision highp sampler3D;
uniform sampler3D uColour;      // linear RGB
uniform sampler3D uStructure;
uniform vec3 uFirst;
uniform vec3 uSize;
uniform float uVoxel;
varying vec3 vWorld;

float toSrgb(float c) { return c <= 0.0031308 ? c * 12.92 : 1.055 * pow(c, 1.0 / 2.4) - 0.055; }
vec3 toSrgb(vec3 c) { return vec3(toSrgb(c.r), toSrgb(c.g), toSrgb(c.b)); }

void main() {
  vec3 g = (vWorld - uFirst) / uVoxel;
  vec3 last = uSize - 1.0;
  if (any(lessThan(g, vec3(0.0))) || any(greaterThan(g, last))) discard;
  vec3 base = min(floor(g), last - 1.0);
  vec3 f = g - base;
  ivec3 b = ivec3(base);
  int region[8];
  float dist[8];
  float weight[8];
  float outline = 0.0;
  for (int c = 0; c < 8; ++c) {
    ivec3 o = ivec3(c & 1, (c >> 1) & 1, (c >> 2) & 1);
    vec3 w = mix(1.0 - f, f, vec3(o));
    weight[c] = w.x * w.y * w.z;
    vec4 s = texelFetch(uStructure, b + o, 0);
    region[c] = int(s.r * 255.0 + 0.5) + 256 * int(s.g * 255.0 + 0.5);
    dist[c] = s.b;  // B / 255, and 255 is one voxel
    outline += weight[c] * (region[c] == 0 ? -s.a : s.a);  // A: the outline distance
  }
  // Solid or empty first: the interpolated signed distance to the outline.
  if (outline <= 0.0) discard;
  // Where all eight voxels are in one region (most points), that region wins: no scores.
  int best = 0;
  bool mixed = false;
  for (int c = 0; c < 8; ++c) {
    if (region[c] == 0) continue;
    mixed = mixed || (best != 0 && region[c] != best);
    if (best == 0) best = region[c];
  }
  float bestScore = -1.0e30;
  for (int c = 0; mixed && c < 8; ++c) {
    if (region[c] == 0) continue;
    float score = 0.0;
    for (int e = 0; e < 8; ++e) score += weight[e] * (region[e] == region[c] ? dist[e] : -dist[e]);
    if (score > bestScore || (score == bestScore && region[c] < best)) {
      best = region[c];
      bestScore = score;
    }
  }
  vec3 sum = vec3(0.0), plain = vec3(0.0);
  float wsum = 0.0, n = 0.0;
  for (int c = 0; c < 8; ++c) {
    if (region[c] != best) continue;
    ivec3 o = ivec3(c & 1, (c >> 1) & 1, (c >> 2) & 1);
    vec3 lin = texelFetch(uColour, b + o, 0).rgb;  // already linear
    sum += weight[c] * lin;
    plain += lin;
    wsum += weight[c];
    n += 1.0;
  }
  vec3 lin = wsum > 0.0 ? sum / wsum : plain / n;
  gl_FragColor = vec4(toSrgb(clamp(lin, 0.0, 1.0)), 1.0);
}`;

// ---------------------------------------------------------------------------------------------
// Small helpers that work across three.js releases (Debian ships r111).

const Texture3D = THREE.Data3DTexture || THREE.DataTexture3D;
const geometry = (name, ...args) =>
  new (THREE[`${name}BufferGeometry`] || THREE[`${name}Geometry`])(...args);
const lightScale = Number.parseInt(THREE.REVISION, 10) >= 155 ? Math.PI : 1;

function texture3D(data, [nx, ny, nz]) {
  const texture = new Texture3D(data, nx, ny, nz);
  texture.format = THREE.RGBAFormat;
  texture.type = data instanceof Uint16Array ? THREE.HalfFloatType : THREE.UnsignedByteType;
  texture.minFilter = texture.magFilter = THREE.NearestFilter;
  texture.generateMipmaps = false;
  texture.unpackAlignment = 1;
  texture.needsUpdate = true;
  return texture;
}

function setOutputSrgb(renderer) {
  if ('outputColorSpace' in renderer) renderer.outputColorSpace = THREE.SRGBColorSpace;
  else if ('outputEncoding' in renderer) renderer.outputEncoding = THREE.sRGBEncoding;
  else { renderer.gammaOutput = true; renderer.gammaFactor = 2.2; }
}

const v3 = (a) => new THREE.Vector3(a[0], a[1], a[2]);
const arr = (v) => [v.x, v.y, v.z];

/// Any unit vector perpendicular to the unit vector `n`.
function perpendicular(n) {
  const helper = Math.abs(n.y) < 0.9 ? new THREE.Vector3(0, 1, 0) : new THREE.Vector3(1, 0, 0);
  return helper.sub(n.clone().multiplyScalar(helper.dot(n))).normalize();
}

// ---------------------------------------------------------------------------------------------
// The view.

const HANDLE_PICK_PX = 10;   // how near the handle's axis a press grabs it
const KNIFE_MIN_PX = 6;      // shorter strokes cut nothing
const KNIFE_TURN_DEG = 35;   // after a cut, the camera turns this far to face the cut
const TURN_MS = 450;

export class CuttingView {
  constructor(canvas, stroke) {
    this.canvas = canvas;
    this.stroke = stroke;    // an SVG <line> over the canvas, the knife's trace
    // A stencil buffer for the stones' cavities (addStone).
    const options = { antialias: true, preserveDrawingBuffer: true, alpha: false, stencil: true };
    const context = canvas.getContext('webgl2', options);
    if (!context) throw new Error('this browser offers no WebGL 2');
    this.renderer = new THREE.WebGLRenderer({ canvas, context, ...options });
    this.renderer.localClippingEnabled = true;
    this.renderer.setClearColor(0xdcdedf);
    setOutputSrgb(this.renderer);
    this.gl = this.renderer.getContext();

    this.scene = new THREE.Scene();
    this.camera = new THREE.PerspectiveCamera(30, 1, 0.001, 100);
    this.scene.add(this.camera);
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x7a736c, 0.85 * lightScale));
    const key = new THREE.DirectionalLight(0xffffff, 0.7 * lightScale);
    key.position.set(0.6, 1, 0.4);
    key.target.position.set(0, 0, -1);
    this.camera.add(key, key.target);

    // The plane: points p with (p - point) . normal > 0 are cut away.
    this.point = new THREE.Vector3();
    this.normal = new THREE.Vector3(0, 0, 1);
    this.clip = new THREE.Plane();

    this.times = [];          // frame times since the last reset (ms)
    this.recent = [];         // the last few, for the panel
    this.pending = false;     // a frame is asked for
    this.dirty = true;        // the drawing buffer is older than the scene
    this.waiters = [];        // resolved after the next frame
    this.turn = null;         // the camera's animation after a knife cut
    this.knifeArmed = false;
    this.drag = null;
    this.listeners = [];      // told of every change and every frame (the panel)

    // Pointer handlers go on before OrbitControls so that they see a press first.
    for (const [type, handler] of [['pointerdown', this.onDown], ['pointermove', this.onMove],
                                   ['pointerup', this.onUp], ['pointercancel', this.onUp]]) {
      canvas.addEventListener(type, handler.bind(this), { capture: true });
    }
    this.controls = new OrbitControls(this.camera, canvas);
    this.controls.addEventListener('change', () => this.requestFrame());
    new ResizeObserver(() => this.requestFrame()).observe(canvas);
  }

  /// Shows `model` (a loaded glTF scene) cut, with its cap read from `volume`.
  setContent(model, volume) {
    const most = this.gl.getParameter(this.gl.MAX_3D_TEXTURE_SIZE);
    if (volume.size.some((n) => n > most)) {
      throw new Error(`the volume (${volume.size.join(' x ')}) exceeds this GPU's 3D textures ` +
                      `(${most} a side)`);
    }
    this.volume = volume;
    this.model = model;
    const meshes = [];
    model.traverse((o) => { if (o.isMesh) meshes.push(o); });
    for (const o of meshes) {
      o.frustumCulled = false;  // quantised positions can leave the bounds unscaled
      const materials = Array.isArray(o.material) ? o.material : [o.material];
      for (const m of materials) {
        m.clippingPlanes = [this.clip];
        m.side = THREE.FrontSide;
      }
      // The inside of the skin, seen through cavities and past the cap's edge: unlit and
      // dimmed, which reads as shade and costs far less than lighting it (software WebGL).
      const inside = materials.map((m) => new THREE.MeshBasicMaterial({
        map: m.map ?? null, color: (m.color ?? new THREE.Color(1, 1, 1)).clone()
          .multiplyScalar(0.55),
        side: THREE.BackSide, clippingPlanes: [this.clip],
      }));
      const back = new THREE.Mesh(o.geometry, Array.isArray(o.material) ? inside : inside[0]);
      back.frustumCulled = false;
      o.add(back);
    }
    this.scene.add(model);

    const box = new THREE.Box3(v3(volume.box.min), v3(volume.box.max));
    this.centre = box.getCenter(new THREE.Vector3());
    this.radius = box.getSize(new THREE.Vector3()).length() / 2;
    this.camera.near = this.radius / 50;
    this.camera.far = this.radius * 40;

    const uniforms = {
      uColour: { value: texture3D(volume.linear, volume.size) },
      uStructure: { value: texture3D(volume.structure, volume.size) },
      uFirst: { value: v3(volume.first) },
      uSize: { value: v3(volume.size) },
      uVoxel: { value: volume.voxel },
    };
    // The cap: the plane within the box where the volume can read as solid (at most a
    // hexagon), drawn as a fan.
    const polygon = new THREE.BufferGeometry();
    polygon.setAttribute('position', new THREE.BufferAttribute(new Float32Array(3 * 12), 3));
    polygon.setIndex(Array.from({ length: 10 }, (_, i) => [0, i + 1, i + 2]).flat());
    // Not drawn where a stone's cavity opens in it (the stencil the stones' passes leave at 1).
    this.cap = new THREE.Mesh(polygon, new THREE.ShaderMaterial({
      uniforms, vertexShader: CAP_VERTEX, fragmentShader: CAP_FRAGMENT, side: THREE.DoubleSide,
      stencilWrite: true, stencilRef: 1, stencilFunc: THREE.NotEqualStencilFunc,
    }));
    this.cap.frustumCulled = false;
    this.scene.add(this.cap);
    this.stones = volume.stones.map((stone) => this.addStone(stone));

    // The plane's frame (a faint square, seen even when the plane misses the object) and the
    // handle (an arrow along the normal, drawn over everything).
    const frame = new THREE.BufferGeometry();
    frame.setAttribute('position', new THREE.BufferAttribute(new Float32Array(12), 3));
    this.frameLine = new THREE.LineLoop(frame, new THREE.LineBasicMaterial(
      { color: 0x404850, transparent: true, opacity: 0.35 }));
    this.frameLine.frustumCulled = false;
    this.scene.add(this.frameLine);
    const length = this.radius * 0.55, grip = this.radius * 0.07;
    const look = { color: 0xf0a020, depthTest: false, transparent: true, opacity: 0.9 };
    const shaft = new THREE.Mesh(geometry('Cylinder', grip * 0.25, grip * 0.25, length, 12),
                                 new THREE.MeshBasicMaterial(look));
    shaft.position.y = length / 2;
    const tip = new THREE.Mesh(geometry('Cone', grip * 0.7, grip * 2, 16),
                               new THREE.MeshBasicMaterial(look));
    tip.position.y = length + grip;
    const foot = new THREE.Mesh(geometry('Sphere', grip * 0.5, 16, 8),
                                new THREE.MeshBasicMaterial(look));
    this.handle = new THREE.Group();
    this.handle.add(shaft, tip, foot);
    this.handle.traverse((o) => { o.renderOrder = 10; });
    this.handleLength = length + 2 * grip;
    this.scene.add(this.handle);

    this.setPlane(this.centre, new THREE.Vector3(0, 0, 1));
    this.frameView();
  }

  /// The meshes that show a stone as a knife leaves it (doc/editor.md, The cutting page): whole
  /// and lit in the half that holds it; in the other, a cavity: the stencil passes mark where the
  /// plane crosses the stone (back faces less front faces of its kept part, seen from the
  /// camera: 1 inside the cross-section), the cap is not drawn there, and the stone's inside,
  /// clipped, shows the flesh's colour against it, lit as a hollow is.
  addStone(stone) {
    const geometryWith = (colours) => {
      const g = new THREE.BufferGeometry();
      g.setAttribute('position', new THREE.BufferAttribute(stone.points, 3));
      g.setAttribute('color', new THREE.BufferAttribute(colours, 3));
      g.setIndex(new THREE.BufferAttribute(stone.triangles, 1));
      g.computeVertexNormals();
      return g;
    };
    const vertexColors = THREE.VertexColors ?? true;
    const own = geometryWith(stone.stone);
    const whole = new THREE.Mesh(own, new THREE.MeshLambertMaterial({ vertexColors }));
    const pass = (side, op) => new THREE.Mesh(own, new THREE.MeshBasicMaterial({
      side, colorWrite: false, depthWrite: false, depthTest: false, clippingPlanes: [this.clip],
      stencilWrite: true, stencilFunc: THREE.AlwaysStencilFunc, stencilZPass: op,
    }));
    const front = pass(THREE.FrontSide, THREE.DecrementWrapStencilOp);
    const back = pass(THREE.BackSide, THREE.IncrementWrapStencilOp);
    const cavity = new THREE.Mesh(geometryWith(stone.flesh), new THREE.MeshLambertMaterial({
      vertexColors, side: THREE.BackSide, clippingPlanes: [this.clip],
    }));
    for (const o of [whole, front, back, cavity]) {
      o.frustumCulled = false;
      this.scene.add(o);
    }
    front.renderOrder = back.renderOrder = -1;  // before the cap reads the stencil
    return { stone, whole, cut: [front, back, cavity], holds: true, kept: 1,
             centre: meanPoint(stone.points) };
  }

  /// Which half holds each stone: the one with the larger share of its volume (a half that
  /// holds exactly half keeps it); shows it whole there, or its cavity.
  placeStones() {
    for (const s of this.stones ?? []) {
      s.kept = keptShare(s.stone.points, s.stone.triangles, s.centre, arr(this.point),
                         arr(this.normal));
      s.holds = s.kept >= 0.5;
      s.whole.visible = s.holds;
      for (const o of s.cut) o.visible = !s.holds;
    }
  }

  /// What the page shows of each stone: its surface, the share of it on the kept side, whether
  /// that half holds it, and the mean of its points (metres).
  stoneState() {
    return (this.stones ?? []).map((s) => ({ surface: s.stone.surface, kept: s.kept,
                                             holds: s.holds, centre: s.centre }));
  }

  // --- the plane ---------------------------------------------------------------------------

  /// Sets the plane through `point` with unit `normal` pointing into the part cut away.
  setPlane(point, normal) {
    const n = normal.clone();
    if (!(n.lengthSq() > 0)) throw new Error('the normal has no length');
    n.normalize();
    // Keep the plane within reach of the object.
    const along = point.clone().sub(this.centre).dot(n);
    const limit = this.radius * 1.02;
    const p = point.clone();
    if (Math.abs(along) > limit) p.addScaledVector(n, Math.sign(along) * limit - along);
    this.point.copy(p);
    this.normal.copy(n);
    this.clip.set(n.clone().negate(), n.dot(p));
    this.placeCap();
    this.placeStones();
    this.requestFrame();
    for (const f of this.listeners) f();
  }

  /// Signed distance of the plane from the object's centre along the normal (metres).
  offset() { return this.point.clone().sub(this.centre).dot(this.normal); }

  /// The point of the plane nearest the object's centre.
  planeCentre() {
    return this.centre.clone().addScaledVector(this.normal, this.offset());
  }

  placeCap() {
    const c = this.planeCentre(), n = this.normal;
    const u = perpendicular(n), w = new THREE.Vector3().crossVectors(n, u);
    const half = this.radius * 1.15;
    const square = [[-1, -1], [1, -1], [1, 1], [-1, 1]].map(([a, b]) =>
      c.clone().addScaledVector(u, a * half).addScaledVector(w, b * half));
    const frame = this.frameLine.geometry.attributes.position;
    square.forEach((p, i) => frame.setXYZ(i, p.x, p.y, p.z));
    frame.needsUpdate = true;

    // Where the plane crosses the edges of the reach box, in order round the plane.
    const { min, max } = this.volume.reach;
    const corner = (k) => new THREE.Vector3(k & 1 ? max[0] : min[0], k & 2 ? max[1] : min[1],
                                            k & 4 ? max[2] : min[2]);
    const points = [];
    for (let a = 0; a < 8; ++a) {
      for (const bit of [1, 2, 4]) {
        if (a & bit) continue;
        const p = corner(a), q = corner(a | bit);
        const dp = p.clone().sub(this.point).dot(n), dq = q.clone().sub(this.point).dot(n);
        if (dp === 0) points.push(p);
        else if (dp * dq < 0) points.push(p.lerp(q, dp / (dp - dq)));
      }
    }
    const mid = points.reduce((m, p) => m.add(p), new THREE.Vector3())
      .multiplyScalar(1 / Math.max(1, points.length));
    const angle = (p) => Math.atan2(p.clone().sub(mid).dot(w), p.clone().sub(mid).dot(u));
    points.sort((p, q) => angle(p) - angle(q));
    const position = this.cap.geometry.attributes.position;
    points.slice(0, 12).forEach((p, i) => position.setXYZ(i, p.x, p.y, p.z));
    position.needsUpdate = true;
    this.cap.geometry.setDrawRange(0, points.length >= 3 ? 3 * (Math.min(points.length, 12) - 2)
                                                         : 0);
    this.handle.position.copy(c);
    this.handle.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), n);
  }

  flip() {
    // The same plane, the other side kept; the camera goes to the mirror image of where it
    // was, so that it still looks at the cut face.
    const d = this.camera.position.clone().sub(this.point).dot(this.normal);
    this.camera.position.addScaledVector(this.normal, -2 * d);
    const t = this.controls.target.clone().sub(this.point).dot(this.normal);
    this.controls.target.addScaledVector(this.normal, -2 * t);
    this.controls.update();
    this.setPlane(this.point, this.normal.clone().negate());
  }

  /// Cuts along a stroke from (x0, y0) to (x1, y1) (canvas CSS pixels): the new plane holds the
  /// stroke and the view direction; the smaller part of the object is cut away. Returns
  /// whether the stroke was long enough to cut.
  knife(x0, y0, x1, y1) {
    if (Math.hypot(x1 - x0, y1 - y0) < KNIFE_MIN_PX) return false;
    const r0 = this.ray(x0, y0), r1 = this.ray(x1, y1);
    const reach = this.camera.position.distanceTo(this.centre);
    const a = r0.origin.clone().addScaledVector(r0.direction, reach);
    const b = r1.origin.clone().addScaledVector(r1.direction, reach);
    const n = new THREE.Vector3().crossVectors(b.clone().sub(a), r0.direction);
    if (!(n.lengthSq() > 1e-24)) return false;
    n.normalize();
    const point = this.centre.clone().addScaledVector(n, a.clone().sub(this.centre).dot(n));
    // Which side is smaller: count solid voxels (a sample of them) on either side.
    const solid = this.volume.solid, count = solid.length / 3;
    const stride = Math.max(1, Math.floor(count / 20000));
    let ahead = 0, behind = 0;
    for (let v = 0; v < count; v += stride) {
      const s = (solid[3 * v] - point.x) * n.x + (solid[3 * v + 1] - point.y) * n.y +
                (solid[3 * v + 2] - point.z) * n.z;
      if (s > 0) ++ahead; else if (s < 0) ++behind;
    }
    if (ahead > behind) n.negate();
    this.setPlane(point, n);
    this.turnToCut();
    return true;
  }

  // --- the camera --------------------------------------------------------------------------

  /// Frames the object: the camera in front of the cut face, a little from above and right.
  frameView() {
    this.controls.target.copy(this.planeCentre());
    const dir = new THREE.Vector3(0.55, 0.45, 1).normalize();
    this.camera.position.copy(this.controls.target).addScaledVector(dir, this.viewDistance());
    this.controls.update();
    this.requestFrame();
  }

  viewDistance() { return this.radius * 3.6; }

  /// Looks at the cut face from the side cut away, `tiltDeg` off its normal (tilted upwards
  /// where the plane is not level).
  faceCap(tiltDeg = 25) {
    const n = this.normal, up = new THREE.Vector3(0, 1, 0);
    let w = up.clone().addScaledVector(n, -up.dot(n));
    if (w.lengthSq() < 1e-6) w = new THREE.Vector3(0, 0, 1);
    w.normalize();
    const t = tiltDeg * Math.PI / 180;
    const dir = n.clone().multiplyScalar(Math.cos(t)).addScaledVector(w, Math.sin(t));
    this.turn = null;
    this.controls.target.copy(this.planeCentre());
    this.camera.position.copy(this.controls.target).addScaledVector(dir, this.viewDistance());
    this.controls.update();
    this.requestFrame();
  }

  /// After a knife cut (the camera lies in the new plane): turns the camera about the orbit
  /// target towards the part cut away so that the cut face comes into view.
  turnToCut() {
    const target = this.controls.target.clone();
    const end = target.clone().addScaledVector(this.normal, -target.clone().sub(this.point)
      .dot(this.normal));
    const offset = this.camera.position.clone().sub(target);
    const axis = new THREE.Vector3().crossVectors(offset, this.normal);
    if (axis.lengthSq() < 1e-12) return;
    axis.normalize();
    this.turn = { start: performance.now(), from: target, to: end, offset, axis };
    this.requestFrame();
  }

  stepTurn(now) {
    const t = Math.min(1, (now - this.turn.start) / TURN_MS);
    const s = t * t * (3 - 2 * t);
    const { from, to, offset, axis } = this.turn;
    const angle = s * KNIFE_TURN_DEG * Math.PI / 180;
    this.controls.target.lerpVectors(from, to, s);
    this.camera.position.copy(this.controls.target)
      .add(offset.clone().applyAxisAngle(axis, angle));
    this.controls.update();
    if (t >= 1) this.turn = null;
  }

  // --- geometry on the screen ----------------------------------------------------------------

  fitCanvas() {
    const w = this.canvas.clientWidth, h = this.canvas.clientHeight;
    const ratio = window.devicePixelRatio || 1;
    if (w !== this.width || h !== this.height || ratio !== this.ratio) {
      this.width = w; this.height = h; this.ratio = ratio;
      this.renderer.setPixelRatio(ratio);
      this.renderer.setSize(w, h, false);
      this.camera.aspect = w / Math.max(1, h);
      this.camera.updateProjectionMatrix();
      this.dirty = true;
    }
    this.camera.updateMatrixWorld();
  }

  /// The canvas CSS pixel of the world point `p`.
  project(p) {
    this.fitCanvas();
    const q = p.clone().project(this.camera);
    return [(q.x + 1) / 2 * this.width, (1 - q.y) / 2 * this.height];
  }

  /// The ray through the canvas CSS point (x, y): {origin, direction (unit)}.
  ray(x, y) {
    this.fitCanvas();
    const ndc = new THREE.Vector3(2 * x / this.width - 1, 1 - 2 * y / this.height, 0.5);
    const origin = this.camera.position.clone();
    const direction = ndc.unproject(this.camera).sub(origin).normalize();
    return { origin, direction };
  }

  /// Where the ray through (x, y) meets the plane, or null.
  pointOnPlane(x, y) {
    const { origin, direction } = this.ray(x, y);
    const den = direction.dot(this.normal);
    if (Math.abs(den) < 1e-12) return null;
    const t = this.point.clone().sub(origin).dot(this.normal) / den;
    return t > 0 ? origin.addScaledVector(direction, t) : null;
  }

  /// The handle's foot and tip on the screen (CSS pixels).
  handleOnScreen() {
    const foot = this.planeCentre();
    const tip = foot.clone().addScaledVector(this.normal, this.handleLength);
    return { foot: this.project(foot), tip: this.project(tip), length_m: this.handleLength };
  }

  onHandle(x, y) {
    if (!this.handle.visible) return false;
    const { foot, tip } = this.handleOnScreen();
    const dx = tip[0] - foot[0], dy = tip[1] - foot[1];
    const t = Math.max(0, Math.min(1, ((x - foot[0]) * dx + (y - foot[1]) * dy) /
                                      Math.max(1e-9, dx * dx + dy * dy)));
    return Math.hypot(x - foot[0] - t * dx, y - foot[1] - t * dy) <= HANDLE_PICK_PX;
  }

  // --- the pointer -------------------------------------------------------------------------

  cssPoint(e) {
    const rect = this.canvas.getBoundingClientRect();
    return [e.clientX - rect.left, e.clientY - rect.top];
  }

  onDown(e) {
    if (e.button !== 0 || !this.volume) return;
    const [x, y] = this.cssPoint(e);
    let mode = null;
    if (this.knifeArmed || e.shiftKey) mode = 'knife';
    else if (e.altKey || e.ctrlKey || this.onHandle(x, y)) mode = 'slide';
    if (!mode) return;
    e.preventDefault();
    e.stopImmediatePropagation();
    this.controls.enabled = false;
    this.canvas.setPointerCapture?.(e.pointerId);
    this.drag = { mode, id: e.pointerId, start: [x, y], startPoint: this.point.clone() };
    if (mode === 'slide') {
      // How the screen moves per metre along the normal, fixed for the whole drag.
      const { foot, tip } = this.handleOnScreen();
      const v = [tip[0] - foot[0], tip[1] - foot[1]];
      const len2 = v[0] * v[0] + v[1] * v[1];
      this.drag.slide = len2 > 64 ? { v, len2 } : null;
      this.canvas.style.cursor = 'grabbing';
    } else {
      this.showStroke(x, y, x, y);
    }
  }

  onMove(e) {
    const [x, y] = this.cssPoint(e);
    if (!this.drag) {
      if (this.volume && !this.knifeArmed) {
        this.canvas.style.cursor = this.onHandle(x, y) ? 'grab' : '';
      }
      return;
    }
    if (e.pointerId !== this.drag.id) return;
    e.preventDefault();
    e.stopImmediatePropagation();
    const dx = x - this.drag.start[0], dy = y - this.drag.start[1];
    if (this.drag.mode === 'knife') {
      this.showStroke(...this.drag.start, x, y);
      return;
    }
    const slide = this.drag.slide;
    const metres = slide
      ? (dx * slide.v[0] + dy * slide.v[1]) / slide.len2 * this.handleLength
      : -dy * 2 * this.radius / Math.max(1, this.height);
    this.setPlane(this.drag.startPoint.clone().addScaledVector(this.normal, metres), this.normal);
  }

  onUp(e) {
    if (!this.drag || e.pointerId !== this.drag.id) return;
    e.preventDefault();
    e.stopImmediatePropagation();
    const drag = this.drag;
    this.drag = null;
    this.controls.enabled = true;
    this.canvas.style.cursor = '';
    if (drag.mode === 'knife') {
      this.showStroke(null);
      const [x, y] = this.cssPoint(e);
      this.knife(...drag.start, x, y);
      this.setKnifeArmed(false);
    }
  }

  showStroke(x0, y0, x1, y1) {
    if (!this.stroke) return;
    if (x0 === null) { this.stroke.style.display = 'none'; return; }
    this.stroke.style.display = '';
    for (const [k, v] of Object.entries({ x1: x0, y1: y0, x2: x1, y2: y1 })) {
      this.stroke.setAttribute(k, v);
    }
  }

  setKnifeArmed(on) {
    this.knifeArmed = on;
    this.canvas.style.cursor = on ? 'crosshair' : '';
    for (const f of this.listeners) f();
  }

  // --- drawing -----------------------------------------------------------------------------

  requestFrame() {
    this.dirty = true;
    if (this.pending) return;
    this.pending = true;
    requestAnimationFrame((now) => {
      this.pending = false;
      if (this.turn) {
        this.stepTurn(now);
        if (this.turn) this.requestFrame();
      }
      this.draw(true);
    });
  }

  /// Draws a frame now. A 1-pixel read afterwards waits for the GPU, so the time measured is
  /// that of the whole frame, not of queueing its commands. `count`: into the frame stats.
  draw(count) {
    const started = performance.now();
    this.fitCanvas();
    this.renderer.render(this.scene, this.camera);
    const gl = this.gl, pixel = new Uint8Array(4);
    gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel);
    const ms = performance.now() - started;
    this.dirty = false;
    if (count) {
      this.times.push(ms);
      this.recent.push(ms);
      if (this.recent.length > 30) this.recent.shift();
    }
    const waiters = this.waiters;
    this.waiters = [];
    for (const f of waiters) f();
    for (const f of this.listeners) f();
  }

  /// The pixel at the canvas CSS point (x, y) as drawn: [r, g, b] (sRGB, 0..255).
  pixel(x, y) {
    if (this.dirty) this.draw(false);
    const gl = this.gl, out = new Uint8Array(4);
    const px = Math.floor(x * this.ratio);
    const py = gl.drawingBufferHeight - 1 - Math.floor(y * this.ratio);
    gl.readPixels(px, py, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, out);
    return [out[0], out[1], out[2]];
  }

  frameStats() {
    const n = this.times.length;
    if (!n) return { frames: 0, mean_ms: null, p95_ms: null };
    const sorted = [...this.times].sort((a, b) => a - b);
    return { frames: n, mean_ms: this.times.reduce((a, b) => a + b, 0) / n,
             p95_ms: sorted[Math.max(0, Math.ceil(0.95 * n) - 1)] };
  }

  recentMs() {
    return this.recent.length ? this.recent.reduce((a, b) => a + b, 0) / this.recent.length
                              : null;
  }

  nextFrame() {
    return new Promise((resolve) => { this.waiters.push(resolve); this.requestFrame(); });
  }
}

// ---------------------------------------------------------------------------------------------
// The page: loading, the panel and the test hooks.

/// The glTF at `url` (binary), parsed by three.js; its relative references resolve against it.
async function loadModel(url) {
  const response = await ask(url, asking);
  if (!response.ok) throw new Error(`${url}: HTTP ${response.status}`);
  const bytes = await response.arrayBuffer();
  const base = new URL('.', new URL(url, location.href)).href;
  return new Promise((resolve, reject) => new GLTFLoader().parse(bytes, base, resolve,
    (e) => reject(new Error(`${url}: ${e?.message ?? e}`))));
}

const $ = (id) => document.getElementById(id);
const fixed = (x, digits) => (x === null || x === undefined ? '–' : x.toFixed(digits));

async function start(hooks) {
  const query = new URLSearchParams(location.search);
  const modelUrl = query.get('model');
  if (!modelUrl) throw new Error('no model given (?model=URL of the .glb)');
  const gltf = await loadModel(modelUrl);
  let volumeUrl = query.get('volume');
  if (!volumeUrl) {
    // The whole-object glTF names its sidecar, relative to itself.
    const sidecar = gltf.scene.userData?.interior_volume?.sidecar;
    if (!sidecar) throw new Error('no volume given (?volume=URL of the sidecar JSON)');
    volumeUrl = new URL(sidecar, new URL(modelUrl, location.href)).href;
  }
  const volume = await loadVolume(volumeUrl);

  const view = new CuttingView($('view'), $('stroke'));
  view.setContent(gltf.scene, volume);
  const name = volume.meta.template ?? '';
  $('template').textContent = name;
  document.title = `cutaway cut: ${name}`;

  let shown = 0;
  const update = () => {
    $('offset').textContent = fixed(view.offset() * 1000, 1);
    $('normal').textContent = arr(view.normal).map((x) => fixed(x, 2)).join(', ');
    $('knife').setAttribute('aria-pressed', String(view.knifeArmed));
    const now = performance.now();
    if (now - shown > 250) {   // the frame time, at a readable pace
      shown = now;
      $('frame-ms').textContent = fixed(view.recentMs(), 1);
    }
  };
  view.listeners.push(update);
  $('flip').addEventListener('click', () => view.flip());
  $('knife').addEventListener('click', () => view.setKnifeArmed(!view.knifeArmed));
  $('reset').addEventListener('click', () => {
    view.setPlane(view.centre, new THREE.Vector3(0, 0, 1));
    view.frameView();
  });
  window.addEventListener('keydown', (e) => {
    if (e.target !== document.body && e.target !== view.canvas) return;
    if (e.key === 'f') view.flip();
    else if (e.key === 'k') view.setKnifeArmed(!view.knifeArmed);
    else if (e.key === 'Escape') view.setKnifeArmed(false);
  });

  Object.assign(hooks, {
    view,
    setPlane: (p, n) => { view.setPlane(v3(p), v3(n)); return hooks.plane(); },
    knife: (x0, y0, x1, y1) => { view.knife(x0, y0, x1, y1); return hooks.plane(); },
    plane: () => ({ point: arr(view.point), normal: arr(view.normal), offset: view.offset() }),
    frameStats: () => view.frameStats(),
    resetFrameStats: () => { view.times = []; },
    sampleVolume: (x, y, z) => readVolume(volume, x, y, z),
    capPixel: (x, y) => view.pixel(x, y),
    project: (x, y, z) => view.project(new THREE.Vector3(x, y, z)),
    // Beyond the basic hooks: what a test needs to aim and to check.
    info: () => ({ template: name, centre: arr(view.centre), radius: view.radius,
                   box: volume.box, size: volume.size, voxel: volume.voxel,
                   canvas: [view.width, view.height], ratio: view.ratio }),
    pointOnPlane: (x, y) => { const p = view.pointOnPlane(x, y); return p && arr(p); },
    ray: (x, y) => {
      const r = view.ray(x, y);
      return { origin: arr(r.origin), direction: arr(r.direction) };
    },
    camera: () => ({ position: arr(view.camera.position), target: arr(view.controls.target) }),
    faceCap: (tiltDeg) => view.faceCap(tiltDeg),
    frameView: () => view.frameView(),
    handle: () => view.handleOnScreen(),
    showHandle: (on) => { view.handle.visible = on; view.requestFrame(); },
    showCap: (on) => { view.cap.visible = on; view.requestFrame(); },
    nextFrame: () => view.nextFrame(),
    idle: async () => { while (view.turn || view.pending) await view.nextFrame(); },
    volumeDigest: () => ({ ...volume.digests }),
    stones: () => view.stoneState(),
  });
  await view.nextFrame();
}

const hooks = {};
hooks.ready = start(hooks).catch((e) => {
  const status = $('status');
  if (status) { status.textContent = String(e?.message ?? e); status.classList.add('bad'); }
  throw e;
});
window.cutting = hooks;
