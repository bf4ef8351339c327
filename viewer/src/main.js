// The hybeam animation page: reads the run embedded in the page (<script id="hybeam-data">,
// written by crates/view/src/animation.rs) and draws the beam as a tube of its section coloured
// by strain (its radius following a taper), the attached masses as spheres, the root (mount)
// frame, the tip trace and, for a vehicle, the car body; with
// play/pause, speed, a time scrubber, the time and the tip values, and an orbiting camera.
// Bundled with three.js by esbuild into dist/viewer.js (npm run build), which the page embeds.

import * as THREE from "three";
import { OrbitControls } from "three/addons/controls/OrbitControls.js";

const data = JSON.parse(document.getElementById("hybeam-data").textContent);

/** A little-endian base64 array of 32- or 64-bit floats. */
function floats(b64, bits) {
  const bin = atob(b64);
  const bytes = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; i++) bytes[i] = bin.charCodeAt(i);
  return bits === 64 ? new Float64Array(bytes.buffer) : new Float32Array(bytes.buffer);
}

const n = data.points; // samples per frame
const times = floats(data.times, 64);
const frames = times.length;
const pos = floats(data.positions, 32); // frames × n × 3
const sec = floats(data.section, 32); // frames × n × 3 (section y axis)
const strain = floats(data.strain, 32); // frames × n
const root = floats(data.root, 32); // frames × 12 (origin, x, y, z axes)
const tipValues = floats(data.tip.values, 64); // frames × names
const tipNames = data.tip.names;
const radius = floats(data.radius, 32); // n
const massRadius = data.mass_radius || []; // per attached mass [m]
const massCentres = data.masses ? floats(data.masses, 32) : new Float32Array(0); // frames × masses × 3
const RING = 12;

// ---- scene, camera, lights
const canvas = document.getElementById("view");
const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio || 1);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0xf4f5f7);
const up = new THREE.Vector3(...data.up);
const camera = new THREE.PerspectiveCamera(40, 1, 1e-4, 1e4);
camera.up.copy(up);
scene.add(new THREE.HemisphereLight(0xffffff, 0x8899aa, 2.2));
const sun = new THREE.DirectionalLight(0xffffff, 1.6);
scene.add(sun);

// bounds of every frame's points: the camera frames them all, unless the root travels far
// (a vehicle): then it frames the first frame (and the body) and follows the root
const box = new THREE.Box3();
for (let i = 0; i < pos.length; i += 3) box.expandByPoint(new THREE.Vector3(pos[i], pos[i + 1], pos[i + 2]));
const first = new THREE.Box3();
for (let i = 0; i < 3 * n; i += 3) first.expandByPoint(new THREE.Vector3(pos[i], pos[i + 1], pos[i + 2]));
if (data.body) first.expandByScalar(0.5 * Math.max(...data.body.size));
const travel = box.getSize(new THREE.Vector3()).length();
const followRoot = travel > 1.5 * first.getSize(new THREE.Vector3()).length();
const frame0 = followRoot ? first : box;
const centre = frame0.getCenter(new THREE.Vector3());
const size = Math.max(frame0.getSize(new THREE.Vector3()).length(), 1e-3);
const follow = document.getElementById("follow");
follow.checked = followRoot;
const side = new THREE.Vector3(0.35, -1, 0.45);
if (up.z === 0) side.set(0.35, 0.45, 1); // y up: look from +z
camera.position.copy(centre).addScaledVector(side.normalize(), 1.6 * size);
sun.position.copy(camera.position).add(new THREE.Vector3(size, size, size));
const controls = new OrbitControls(camera, canvas);
controls.target.copy(centre);
controls.update();
const grid = new THREE.GridHelper(2 * size, 20, 0xb0b4ba, 0xd5d8dc);
if (up.z !== 0) grid.rotation.x = Math.PI / 2;
grid.position.copy(centre).addScaledVector(up, -0.6 * size);
scene.add(grid);

// ---- the tube: RING vertices around each sample, segments' rings joined
let rMax = 0;
for (const r of radius) rMax = Math.max(rMax, r);
const autoScale = Math.max(1, (0.006 * size) / Math.max(rMax, 1e-9));
let thickness = Math.round(autoScale);
const verts = new Float32Array(n * RING * 3);
const colors = new Float32Array(n * RING * 3);
const index = [];
for (const [a, b] of data.segments) {
  for (let i = a; i < b - 1; i++) {
    for (let k = 0; k < RING; k++) {
      const k1 = (k + 1) % RING;
      const p = i * RING, q = (i + 1) * RING;
      index.push(p + k, q + k, q + k1, p + k, q + k1, p + k1);
    }
  }
}
const tube = new THREE.BufferGeometry();
tube.setAttribute("position", new THREE.BufferAttribute(verts, 3));
tube.setAttribute("color", new THREE.BufferAttribute(colors, 3));
tube.setIndex(index);
const beam = new THREE.Mesh(tube, new THREE.MeshStandardMaterial({ vertexColors: true, roughness: 0.55, metalness: 0.1, side: THREE.DoubleSide }));
scene.add(beam);
// a stripe along the section's y axis: the twist shows as its winding
const stripeGeom = new THREE.BufferGeometry();
const stripe = new Float32Array(n * 3);
stripeGeom.setAttribute("position", new THREE.BufferAttribute(stripe, 3));
scene.add(new THREE.Line(stripeGeom, new THREE.LineBasicMaterial({ color: 0x202020 })));

// ---- strain colour scale (0 … the run's largest), a viridis-like ramp
let sMax = 0;
for (const s of strain) sMax = Math.max(sMax, Math.abs(s));
sMax = sMax || 1;
const RAMP = [[0.267, 0.005, 0.329], [0.230, 0.322, 0.546], [0.128, 0.567, 0.551], [0.369, 0.789, 0.383], [0.993, 0.906, 0.144]];
function ramp(x) {
  const t = Math.min(Math.max(x, 0), 1) * (RAMP.length - 1);
  const i = Math.min(Math.floor(t), RAMP.length - 2), f = t - i;
  return RAMP[i].map((c, k) => c + f * (RAMP[i + 1][k] - c));
}
document.getElementById("legend-max").textContent = sMax.toExponential(2);
document.getElementById("legend-label").textContent = data.strain_label;
const legend = document.getElementById("legend-bar");
legend.style.background = `linear-gradient(to right, ${RAMP.map((c) => `rgb(${c.map((v) => Math.round(255 * v)).join(",")})`).join(",")})`;

// ---- root frame, tip trace, car body
const axes = new THREE.AxesHelper(0.15 * size);
axes.matrixAutoUpdate = false;
scene.add(axes);
let body = null;
if (data.body) {
  const [lx, ly, lz] = data.body.size;
  body = new THREE.Mesh(new THREE.BoxGeometry(lx, ly, lz), new THREE.MeshStandardMaterial({ color: 0x4a78b5, transparent: true, opacity: 0.55 }));
  body.matrixAutoUpdate = false;
  scene.add(body);
}
const tipIndex = n - 1;
const trace = new Float32Array(frames * 3);
for (let f = 0; f < frames; f++) for (let c = 0; c < 3; c++) trace[3 * f + c] = pos[(f * n + tipIndex) * 3 + c];
const traceGeom = new THREE.BufferGeometry();
traceGeom.setAttribute("position", new THREE.BufferAttribute(trace, 3));
scene.add(new THREE.Line(traceGeom, new THREE.LineBasicMaterial({ color: 0xd0402b })));

// the joints between segments: a sphere at each downstream segment's first point
const joints = data.segments.slice(1).map(([a]) => {
  const m = new THREE.Mesh(new THREE.SphereGeometry(1, 16, 12), new THREE.MeshStandardMaterial({ color: 0x303338 }));
  scene.add(m);
  return { index: a, mesh: m };
});

// the attached masses: spheres of their drawn radius (at least 1 % of the view)
const masses = massRadius.map((r) => {
  const m = new THREE.Mesh(new THREE.SphereGeometry(1, 20, 14), new THREE.MeshStandardMaterial({ color: 0xe0a030, roughness: 0.5 }));
  m.scale.setScalar(Math.max(r, 0.01 * size));
  scene.add(m);
  return m;
});

// ---- one frame onto the geometry
const t = new THREE.Vector3(), d2 = new THREE.Vector3(), d3 = new THREE.Vector3(), p = new THREE.Vector3();
function tangent(f, i) {
  // central difference within the point's segment
  const seg = data.segments.find(([a, b]) => i >= a && i < b);
  const a = Math.max(i - 1, seg[0]), b = Math.min(i + 1, seg[1] - 1);
  const o = f * n * 3;
  t.set(pos[o + 3 * b] - pos[o + 3 * a], pos[o + 3 * b + 1] - pos[o + 3 * a + 1], pos[o + 3 * b + 2] - pos[o + 3 * a + 2]).normalize();
}
let current = -1;
let lastRoot = null;
function show(f) {
  current = f;
  const o = f * n * 3;
  for (let i = 0; i < n; i++) {
    tangent(f, i);
    d2.set(sec[o + 3 * i], sec[o + 3 * i + 1], sec[o + 3 * i + 2]);
    d2.addScaledVector(t, -d2.dot(t)).normalize();
    d3.crossVectors(t, d2);
    p.set(pos[o + 3 * i], pos[o + 3 * i + 1], pos[o + 3 * i + 2]);
    const r = radius[i] * thickness;
    const col = ramp(Math.abs(strain[f * n + i]) / sMax);
    for (let k = 0; k < RING; k++) {
      const phi = (2 * Math.PI * k) / RING, c = Math.cos(phi) * r, s = Math.sin(phi) * r;
      const v = 3 * (i * RING + k);
      verts[v] = p.x + c * d2.x + s * d3.x;
      verts[v + 1] = p.y + c * d2.y + s * d3.y;
      verts[v + 2] = p.z + c * d2.z + s * d3.z;
      colors.set(col, v);
    }
    stripe[3 * i] = p.x + 1.05 * r * d2.x;
    stripe[3 * i + 1] = p.y + 1.05 * r * d2.y;
    stripe[3 * i + 2] = p.z + 1.05 * r * d2.z;
  }
  tube.attributes.position.needsUpdate = true;
  tube.attributes.color.needsUpdate = true;
  tube.computeVertexNormals();
  tube.computeBoundingSphere();
  stripeGeom.attributes.position.needsUpdate = true;
  stripeGeom.computeBoundingSphere();
  const R = root.subarray(12 * f, 12 * f + 12);
  if (follow.checked && lastRoot) {
    const d = new THREE.Vector3(R[0] - lastRoot[0], R[1] - lastRoot[1], R[2] - lastRoot[2]);
    camera.position.add(d);
    controls.target.add(d);
    sun.position.add(d);
    grid.position.add(d);
  }
  lastRoot = [R[0], R[1], R[2]];
  const m = new THREE.Matrix4().set(R[3], R[6], R[9], R[0], R[4], R[7], R[10], R[1], R[5], R[8], R[11], R[2], 0, 0, 0, 1);
  axes.matrix.copy(m);
  if (body) {
    const c = data.body.centre;
    body.matrix.copy(m).multiply(new THREE.Matrix4().makeTranslation(c[0], c[1], c[2]));
  }
  for (const j of joints) {
    const i = j.index;
    j.mesh.position.set(pos[o + 3 * i], pos[o + 3 * i + 1], pos[o + 3 * i + 2]);
    j.mesh.scale.setScalar(1.8 * radius[i] * thickness);
  }
  const nm = masses.length;
  masses.forEach((m, k) => {
    const c = 3 * (f * nm + k);
    m.position.set(massCentres[c], massCentres[c + 1], massCentres[c + 2]);
  });
  traceGeom.setDrawRange(0, f + 1);
  document.getElementById("time").textContent = `t = ${times[f].toFixed(4)} s`;
  const rows = tipNames.map((name, k) => `${name} = ${tipValues[f * tipNames.length + k].toExponential(6)}`);
  document.getElementById("tip").textContent = rows.join("\n");
  scrub.value = String(f);
}

// ---- controls: play/pause, speed, scrub, thickness
const scrub = document.getElementById("scrub");
scrub.max = String(frames - 1);
const play = document.getElementById("play");
const speed = document.getElementById("speed");
const thick = document.getElementById("thickness");
thick.value = String(thickness);
document.getElementById("thickness-label").textContent = `×${thickness}`;
let playing = false, simTime = times[0], last = null;
play.addEventListener("click", () => {
  playing = !playing;
  play.textContent = playing ? "Pause" : "Play";
  if (playing && current >= frames - 1) simTime = times[0];
  last = null;
});
scrub.addEventListener("input", () => {
  show(Number(scrub.value));
  simTime = times[current];
});
thick.addEventListener("input", () => {
  thickness = Number(thick.value);
  document.getElementById("thickness-label").textContent = `×${thickness}`;
  show(current);
});
function frameAt(time) {
  let lo = 0, hi = frames - 1;
  while (lo < hi) {
    const mid = (lo + hi + 1) >> 1;
    if (times[mid] <= time) lo = mid; else hi = mid - 1;
  }
  return lo;
}
function resize() {
  const w = canvas.clientWidth, h = canvas.clientHeight;
  if (canvas.width !== w || canvas.height !== h) {
    renderer.setSize(w, h, false);
    camera.aspect = w / Math.max(h, 1);
    camera.updateProjectionMatrix();
  }
}
function loop(now) {
  resize();
  if (playing) {
    if (last !== null) simTime += ((now - last) / 1000) * Number(speed.value);
    last = now;
    const f = frameAt(simTime);
    if (f !== current) show(f);
    if (f >= frames - 1) {
      playing = false;
      play.textContent = "Play";
    }
  }
  controls.update();
  renderer.render(scene, camera);
  requestAnimationFrame(loop);
}
show(0);
requestAnimationFrame(loop);
document.getElementById("title").textContent = data.title;
window.hybeam = { frames, frame: () => current, show };
