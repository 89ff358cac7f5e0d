// Loads one glTF file (.glb, or .gltf with its .bin beside it) with three.js's GLTFLoader in
// headless Chromium: a real glTF client, not a schema check.
// Usage: node tests/tools/load_gltf_three.mjs FILE.glb|FILE.gltf [--screenshot OUT.png [W H]]
// With --screenshot it also renders the file with its camera and lights (WebGL through
// SwiftShader) to OUT.png, W x H pixels (800 x 600 by default), and reports object_luminance
// (mean Rec. 709 luma of the 8-bit sRGB pixels that are not background, 0..255) and
// object_fraction (their share of the frame).
// Prints one JSON line:
//   {ok, meshes, nodes, cameras, lights, triangles, mesh_objects, camera_position,
//    camera_direction, light_directions, compressed_textures, warnings, seconds, error}
// meshes / nodes: glTF meshes and nodes three.js built; cameras / lights: camera and light
// objects in the loaded scene; triangles: triangles of all mesh objects (instances counted);
// camera_direction and light_directions: world-space view / light directions (unit vectors, one
// per directional light); compressed_textures: the GPU (KTX2) textures its materials use;
// warnings: console warnings and errors of the page.
// Exit code 0 when the file loaded, 1 otherwise.
//
// Network: a node http server on 127.0.0.1 (ephemeral port) serves the page, node_modules/three
// and the file's folder; Chromium is shut off from everything else (chromium.mjs).
import fs from 'node:fs';
import http from 'node:http';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { openPage } from './chromium.mjs';

const started = Date.now();
const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..', '..');
const threeDir = path.join(root, 'node_modules', 'three');
const TIMEOUT_MS = 60000;

function report(fields) {
  const out = {
    ok: false, meshes: 0, nodes: 0, cameras: 0, lights: 0, triangles: 0, mesh_objects: 0,
    camera_position: null, camera_direction: null, light_directions: [], warnings: [],
    seconds: 0, error: '', ...fields,
  };
  out.seconds = (Date.now() - started) / 1000;
  console.log(JSON.stringify(out));
  return out.ok ? 0 : 1;
}

const PAGE = `<!doctype html>
<html><head><meta charset="utf-8">
<script type="importmap">
{"imports": {"three": "/three/build/three.module.js", "three/addons/": "/three/examples/jsm/"}}
</script></head><body>
<script type="module">
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { KTX2Loader } from 'three/addons/loaders/KTX2Loader.js';
import { MeshoptDecoder } from 'three/addons/libs/meshopt_decoder.module.js';
// One renderer for every load and picture: KHR_texture_basisu's KTX2Loader transcodes to what
// it supports. EXT_meshopt_compression needs the decoder; KHR_mesh_quantization needs nothing.
const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
const ktx2 = new KTX2Loader().setTranscoderPath('/three/examples/jsm/libs/basis/')
  .detectSupport(renderer);
const newLoader = () => new GLTFLoader().setMeshoptDecoder(MeshoptDecoder).setKTX2Loader(ktx2);
window.loadGltf = async (url) => {
  const gltf = await newLoader().loadAsync(url);
  const meshes = await gltf.parser.getDependencies('mesh');
  const nodes = await gltf.parser.getDependencies('node');
  gltf.scene.updateMatrixWorld(true);
  const r = { meshes: meshes.length, nodes: nodes.length, cameras: 0, lights: 0, triangles: 0,
              mesh_objects: 0, camera_position: null, camera_direction: null,
              light_directions: [], compressed_textures: 0 };
  const textures = new Set();
  const v = (p) => [p.x, p.y, p.z];
  gltf.scene.traverse((o) => {
    if (o.isMesh) {
      r.mesh_objects += 1;
      for (const key of ['map', 'normalMap', 'roughnessMap']) {
        const t = o.material?.[key];
        if (t?.isCompressedTexture) textures.add(t);
      }
      const g = o.geometry;
      r.triangles += (g.index ? g.index.count : g.attributes.position.count) / 3;
    }
    if (o.isCamera) {
      r.cameras += 1;
      r.camera_position = v(o.getWorldPosition(new THREE.Vector3()));
      r.camera_direction = v(o.getWorldDirection(new THREE.Vector3()));
    }
    if (o.isLight) {
      r.lights += 1;
      if (o.isDirectionalLight) {
        o.target.updateMatrixWorld(true);
        const d = o.target.getWorldPosition(new THREE.Vector3())
          .sub(o.getWorldPosition(new THREE.Vector3())).normalize();
        r.light_directions.push(v(d));
      }
    }
  });
  r.compressed_textures = textures.size;  // GPU textures (KTX2), as the GPU keeps them
  return r;
};
// Renders the file (its backdrop left out) with its first camera and lights over a grey
// background, as PNG data URL, the way doc/lighting.md tells a three.js user to: the scene's
// extras give the exposure (toneMappingExposure under linear tone mapping) for its lights in
// lux, and the sky illuminance in lux (ambient_lux) that a hemisphere light supplies. Without ambient_lux the
// hemisphere light gives 0.6 after exposure; without exposure, the exposure is 1.
window.renderGltf = async (url, width, height) => {
  const gltf = await newLoader().loadAsync(url);
  const view = gltf.scene.userData ?? {};
  renderer.setSize(width, height);
  renderer.outputColorSpace = THREE.SRGBColorSpace;
  renderer.toneMapping = THREE.LinearToneMapping;
  renderer.toneMappingExposure = view.exposure ?? 1;
  document.body.appendChild(renderer.domElement);
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0.72, 0.72, 0.74);  // the clear colour: not tone mapped
  // The backdrop (extras.backdrop) stays out: the frame measures the objects alone.
  gltf.scene.traverse((o) => { if (o.userData?.backdrop === true) o.visible = false; });
  scene.add(gltf.scene);
  scene.add(new THREE.HemisphereLight(0xffffff, 0x808080,
                                       view.ambient_lux ?? 0.6 / renderer.toneMappingExposure));
  const camera = gltf.cameras[0];
  camera.aspect = width / height;
  camera.updateProjectionMatrix();
  renderer.render(scene, camera);
  // Mean Rec. 709 luminance of the 8-bit sRGB values (0..255) over the pixels that are not
  // the background's colour: the objects' exposure.
  const flat = document.createElement('canvas');
  flat.width = width;
  flat.height = height;
  const context = flat.getContext('2d');
  context.drawImage(renderer.domElement, 0, 0);
  const px = context.getImageData(0, 0, width, height).data;
  const bg = [px[0], px[1], px[2]];  // a corner: the background in every cutaway view
  let sum = 0, count = 0;
  for (let i = 0; i < px.length; i += 4) {
    if (px[i] === bg[0] && px[i + 1] === bg[1] && px[i + 2] === bg[2]) continue;
    sum += 0.2126 * px[i] + 0.7152 * px[i + 1] + 0.0722 * px[i + 2];
    count += 1;
  }
  return { png: renderer.domElement.toDataURL('image/png'),
           object_luminance: count ? sum / count : 0, object_fraction: count / (width * height) };
};
window.pageReady = true;
</script></body></html>`;

const TYPES = {
  '.js': 'text/javascript', '.mjs': 'text/javascript', '.html': 'text/html',
  '.glb': 'model/gltf-binary', '.gltf': 'model/gltf+json', '.bin': 'application/octet-stream',
  '.png': 'image/png', '.jpg': 'image/jpeg', '.json': 'application/json',
  '.wasm': 'application/wasm', '.ktx2': 'image/ktx2',
};

/// The file below `base` that `rel` (URL-decoded) names, or null when it leaves `base`.
function inside(base, rel) {
  const p = path.resolve(base, '.' + path.sep + rel);
  return p === base || p.startsWith(base + path.sep) ? p : null;
}

function serve(fileDir) {
  return http.createServer((req, res) => {
    let target = null;
    try {
      const url = new URL(req.url, 'http://127.0.0.1');
      const name = decodeURIComponent(url.pathname);
      if (name === '/') {
        res.writeHead(200, { 'content-type': 'text/html' });
        res.end(PAGE);
        return;
      }
      if (name.startsWith('/three/')) target = inside(threeDir, name.slice(7));
      else if (name.startsWith('/file/')) target = inside(fileDir, name.slice(6));
    } catch {
      target = null;
    }
    if (!target || !fs.existsSync(target) || !fs.statSync(target).isFile()) {
      res.writeHead(404);
      res.end();
      return;
    }
    res.writeHead(200, {
      'content-type': TYPES[path.extname(target).toLowerCase()] ?? 'application/octet-stream',
    });
    fs.createReadStream(target).pipe(res);
  });
}

async function main() {
  const file = process.argv[2];
  // --screenshot OUT.png [WIDTH HEIGHT]: also render the file to OUT.png (WebGL in software).
  const shot = process.argv[3] === '--screenshot' ? process.argv[4] : null;
  const shotWidth = Number(process.argv[5] ?? 800), shotHeight = Number(process.argv[6] ?? 600);
  if (!file) {
    return report({ error: 'usage: node tests/tools/load_gltf_three.mjs FILE.glb|FILE.gltf' });
  }
  const abs = path.resolve(file);
  if (!fs.existsSync(abs)) return report({ error: `no such file: ${abs}` });
  if (!fs.existsSync(path.join(threeDir, 'examples', 'jsm', 'loaders', 'GLTFLoader.js'))) {
    return report({ error: `three.js missing in ${threeDir} (scripts/install-deps.sh --test)` });
  }

  const server = serve(path.dirname(abs));
  await new Promise((resolve, reject) => {
    server.once('error', reject);
    server.listen(0, '127.0.0.1', resolve);
  });
  const origin = `http://127.0.0.1:${server.address().port}`;
  let session = null;
  const warnings = [];
  const timer = setTimeout(() => {
    process.exit(report({ error: `timed out after ${TIMEOUT_MS / 1000} s`, warnings }));
  }, TIMEOUT_MS);
  try {
    session = await openPage(origin, { webgl: !!shot, timeoutMs: TIMEOUT_MS, warnings });
    const { page } = session;
    await page.goto(origin + '/', { timeout: TIMEOUT_MS });
    await page.waitForFunction(() => window.pageReady === true, null, { timeout: TIMEOUT_MS });
    const url = '/file/' + encodeURIComponent(path.basename(abs));
    const result = await page.evaluate((u) => window.loadGltf(u), url);
    if (shot) {
      const frame = await page.evaluate(([u, w, h]) => window.renderGltf(u, w, h),
                                        [url, shotWidth, shotHeight]);
      fs.writeFileSync(shot, Buffer.from(frame.png.split(',')[1], 'base64'));
      result.object_luminance = frame.object_luminance;
      result.object_fraction = frame.object_fraction;
    }
    return report({ ok: true, ...result, warnings });
  } catch (e) {
    return report({ error: String(e?.message ?? e).split('\n')[0], warnings });
  } finally {
    clearTimeout(timer);
    if (session) await session.close();
    server.close();
  }
}

process.exitCode = await main();
