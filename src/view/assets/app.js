// The page of `ontogeny view`: a creature in 3D (three.js), its brain, and the controls of
// the kind of page the server shows (growth, recording, run). Everything the tests read is on
// document.body.dataset: kind, parts (parts drawn now), frame, frames, ready, error, findings
// (how many findings and problems the Findings box lists, on a grammar's page), webgl; on a
// run page also generation and individual (the one shown), and walk ("G/R" while the walk of
// rank R of generation G is shown).
import * as THREE from 'three';
import { OrbitControls } from '/three/OrbitControls.js';
import { definesQuery, showDefines } from '/defines.js';
import { drawBrain } from '/brain.js';

const params = new URLSearchParams(location.search);
const still = params.has('still');
const body = document.body;
const $ = (id) => document.getElementById(id);

const COLORS = {
  root: 0x1f3f7a, part: 0x4f86d9, growing: 0xf08c1e,
  joint: 0xdd2222, jointGrowing: 0xf08c1e, fused: 0x999999,
  projectile: 0x8a5a2b, trail: 0x8a5a2b, target: 0xdd2222, path: 0x0078d7,
};

// ---------------------------------------------------------------- the 3D scene

const sceneBox = $('scene');
const scene = new THREE.Scene();
scene.background = new THREE.Color(0xe9edf2);
const camera = new THREE.PerspectiveCamera(40, 1, 0.01, 1000);
let renderer = null;
let controls = null;
try {
  renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.shadowMap.enabled = true;
  sceneBox.appendChild(renderer.domElement);
  controls = new OrbitControls(camera, renderer.domElement);
  controls.addEventListener('change', requestRender);
  body.dataset.webgl = 'yes';
} catch (e) {
  body.dataset.webgl = 'no';
  renderer = null;
  const note = document.createElement('div');
  note.style.cssText = 'padding:2em;color:#a00';
  note.textContent = 'WebGL is not available in this browser: the 3D view cannot be drawn (' + e.message + ')';
  sceneBox.appendChild(note);
}

scene.add(new THREE.HemisphereLight(0xffffff, 0x8899aa, 1.6));
const sun = new THREE.DirectionalLight(0xffffff, 1.8);
sun.castShadow = true;
sun.shadow.mapSize.set(1024, 1024);
scene.add(sun);
scene.add(sun.target);
const ground = new THREE.Mesh(
  new THREE.PlaneGeometry(1, 1),
  new THREE.MeshLambertMaterial({ color: 0xd5dbe3 }));
ground.rotation.x = -Math.PI / 2;
ground.receiveShadow = true;
scene.add(ground);
let grid = null;

// The creature's meshes: one per part (counted in data-parts), one per joint marker.
const creatureGroup = new THREE.Group();
scene.add(creatureGroup);
const extrasGroup = new THREE.Group(); // target, projectile, trail
scene.add(extrasGroup);

let renderPending = false;
function requestRender() {
  if (!renderer || renderPending) return;
  renderPending = true;
  requestAnimationFrame(() => {
    renderPending = false;
    renderer.render(scene, camera);
  });
}

function resize() {
  const w = sceneBox.clientWidth || 1, h = sceneBox.clientHeight || 1;
  camera.aspect = w / h;
  camera.updateProjectionMatrix();
  if (renderer) renderer.setSize(w, h, false);
  requestRender();
}
window.addEventListener('resize', resize);

const v3 = (a) => new THREE.Vector3(a[0], a[1], a[2]);
const quat = (q) => new THREE.Quaternion(q[0], q[1], q[2], q[3]); // nalgebra: [i, j, k, w]

function clearGroup(group) {
  for (const child of [...group.children]) {
    group.remove(child);
    if (child.userData.shared) continue; // its geometry and material serve every creature
    child.geometry?.dispose();
    child.material?.dispose();
  }
}

// Parts and joint markers share one unit geometry each, scaled per mesh, and one material
// per colour: a plant of thousands of parts makes no geometry or material per part.
const UNIT_BOX = new THREE.BoxGeometry(1, 1, 1);
const UNIT_SPHERE = new THREE.SphereGeometry(1, 16, 12);
const sharedMaterials = new Map();
function sharedMaterial(kind, color) {
  const key = `${kind}:${color}`;
  if (!sharedMaterials.has(key)) {
    sharedMaterials.set(key, kind === 'part'
      ? new THREE.MeshStandardMaterial({ color, roughness: 0.7, metalness: 0.0 })
      : new THREE.MeshBasicMaterial({ color, depthTest: false }));
  }
  return sharedMaterials.get(key);
}

// Half the middle dimension of the smaller of the parts a joint joins (a bar's width).
function jointRadius(creature, j) {
  const middle = (p) => (p ? [...p.size].sort((a, b) => a - b)[1] : Infinity);
  return Math.min(middle(creature.parts[j.parent]), middle(creature.parts[j.child])) / 2;
}

// Draws a creature's parts and joints; returns the part meshes (in part order).
function drawCreature(creature) {
  clearGroup(creatureGroup);
  const meshes = creature.parts.map((p, i) => {
    const color = p.growing ? COLORS.growing : (i === 0 ? COLORS.root : COLORS.part);
    const mesh = new THREE.Mesh(UNIT_BOX, sharedMaterial('part', color));
    mesh.userData.shared = true;
    mesh.scale.set(p.size[0], p.size[1], p.size[2]);
    mesh.position.copy(v3(p.position));
    mesh.quaternion.copy(quat(p.orientation));
    mesh.castShadow = true;
    mesh.receiveShadow = true;
    mesh.userData.part = i;
    creatureGroup.add(mesh);
    return mesh;
  });
  // Joint markers: a fraction of a typical part's thickness, and small beside the whole body.
  const diagonal = boundsOf([creature]).getSize(new THREE.Vector3()).length();
  const scale = Math.min(typicalSize(creature), 0.1 * diagonal);
  for (const j of creature.joints) {
    const color = j.growing ? COLORS.jointGrowing : (j.kind === 'rigid' ? COLORS.fused : COLORS.joint);
    // Never larger than the parts it joins: at most half the smaller one's middle dimension.
    const r = Math.min((j.kind === 'rigid' ? 0.15 : 0.3) * scale, jointRadius(creature, j));
    // Drawn over the parts, as they sit inside them.
    const marker = new THREE.Mesh(UNIT_SPHERE, sharedMaterial('marker', color));
    marker.userData.shared = true;
    marker.scale.setScalar(r);
    marker.renderOrder = 1;
    marker.position.copy(v3(j.anchor));
    marker.userData.joint = { parent: j.parent, child: j.child };
    // In a recording the marker rides on its parent part.
    if (meshes[j.parent]) {
      const parent = meshes[j.parent];
      parent.updateMatrixWorld();
      marker.userData.local = parent.worldToLocal(marker.position.clone());
    }
    creatureGroup.add(marker);
  }
  body.dataset.parts = String(meshes.length);
  return meshes;
}

function typicalSize(creature) {
  if (!creature.parts.length) return 0.1;
  const sizes = creature.parts.map((p) => Math.min(p.size[0], p.size[1], p.size[2]));
  sizes.sort((a, b) => a - b);
  return Math.max(sizes[Math.floor(sizes.length / 2)], 1e-3);
}

// The box around every part of every given creature (their exact corners).
function boundsOf(creatures) {
  const box = new THREE.Box3();
  const corner = new THREE.Vector3();
  for (const c of creatures) {
    for (const p of c.parts) {
      const q = quat(p.orientation || [0, 0, 0, 1]);
      const centre = v3(p.position);
      for (let k = 0; k < 8; k++) {
        corner.set((k & 1 ? 0.5 : -0.5) * p.size[0], (k & 2 ? 0.5 : -0.5) * p.size[1], (k & 4 ? 0.5 : -0.5) * p.size[2]);
        box.expandByPoint(corner.applyQuaternion(q).add(centre));
      }
    }
  }
  if (box.isEmpty()) box.set(new THREE.Vector3(-0.5, 0, -0.5), new THREE.Vector3(0.5, 1, 0.5));
  return box;
}

// A world's geometry (the recording's `scene`) as meshes in `group`: a slope's tilted plane
// with its grid, steps and obstacles as boxes, rough ground as a mesh of its samples, objects
// as balls and boxes (returned, to be moved frame by frame), water as a blue scene with no
// ground. The level ground stays for a world whose ground is level.
function drawWorld(world, group) {
  const shaped = world.ground !== 'level';
  ground.visible = !shaped;
  if (grid) grid.visible = !shaped;
  scene.background = new THREE.Color(world.water ? 0x9cc3e6 : 0xe9edf2);
  const floor = new THREE.MeshLambertMaterial({ color: 0xd5dbe3, side: THREE.DoubleSide });
  const stone = new THREE.MeshLambertMaterial({ color: 0x968773 });
  const box = (b, material) => {
    // Boxes reaching far are cut to 50 m a side, which is as far as the view goes.
    const h = b.half.map((x) => Math.min(x, 50));
    const mesh = new THREE.Mesh(new THREE.BoxGeometry(2 * h[0], 2 * h[1], 2 * h[2]), material);
    mesh.position.set(b.centre[0], b.centre[1], b.centre[2]);
    mesh.rotation.y = -b.direction * Math.PI / 180;
    mesh.receiveShadow = true;
    mesh.castShadow = material === stone;
    group.add(mesh);
  };
  if (world.ground === 'slope' && world.normal) {
    const plane = new THREE.Mesh(new THREE.PlaneGeometry(100, 100), floor);
    const lines = new THREE.GridHelper(100, 100, 0xaab3bf, 0xc3cad3);
    const tilt = new THREE.Quaternion().setFromUnitVectors(new THREE.Vector3(0, 1, 0), v3(world.normal));
    plane.quaternion.copy(tilt).multiply(new THREE.Quaternion().setFromAxisAngle(new THREE.Vector3(1, 0, 0), -Math.PI / 2));
    lines.quaternion.copy(tilt);
    lines.position.copy(v3(world.normal).multiplyScalar(0.002));
    plane.receiveShadow = true;
    group.add(plane, lines);
  }
  for (const b of world.boxes || []) box(b, floor);
  const field = world.heightfield;
  if (field) {
    const n = field.samples;
    const geometry = new THREE.PlaneGeometry(field.side, field.side, n - 1, n - 1);
    geometry.rotateX(-Math.PI / 2); // rows along +z, columns along +x
    const position = geometry.attributes.position;
    for (let i = 0; i < position.count; i++) position.setY(i, field.heights[i]);
    geometry.computeVertexNormals();
    const mesh = new THREE.Mesh(geometry, floor);
    mesh.receiveShadow = true;
    group.add(mesh);
  }
  for (const b of world.obstacles || []) box(b, stone);
  const gold = new THREE.MeshStandardMaterial({ color: 0xe1aa32 });
  return (world.objects || []).map((o) => {
    const geometry = o.shape === 'ball'
      ? new THREE.SphereGeometry(o.half, 24, 16)
      : new THREE.BoxGeometry(2 * o.half, 2 * o.half, 2 * o.half);
    const mesh = new THREE.Mesh(geometry, gold);
    mesh.position.copy(v3(o.centre));
    mesh.castShadow = true;
    group.add(mesh);
    return mesh;
  });
}

// A 3/4 view of the box, the ground (at height groundY) and its grid sized to it.
function frame(box, groundY) {
  const centre = box.getCenter(new THREE.Vector3());
  const size = Math.max(box.getSize(new THREE.Vector3()).length(), 0.2);
  const distance = size * 0.7 / Math.tan((camera.fov * Math.PI / 180) / 2) + size * 0.2;
  const dir = new THREE.Vector3(1, 0.75, 1.3).normalize();
  camera.position.copy(centre).addScaledVector(dir, distance);
  camera.near = Math.max(distance / 1000, 1e-3);
  camera.far = distance * 100;
  camera.updateProjectionMatrix();
  camera.lookAt(centre);
  if (controls) { controls.target.copy(centre); controls.update(); }
  const extent = Math.max(size * 6, 2);
  ground.scale.set(extent, extent, 1);
  ground.position.set(centre.x, groundY, centre.z);
  if (grid) { scene.remove(grid); grid.geometry.dispose(); grid.material.dispose(); }
  const step = Math.pow(10, Math.floor(Math.log10(extent / 10)));
  const divisions = Math.min(200, Math.round(extent / step));
  grid = new THREE.GridHelper(divisions * step, divisions, 0xaab3bf, 0xc3cad3);
  grid.position.set(centre.x, groundY + 0.0005 * size, centre.z);
  grid.userData.step = step;
  scene.add(grid);
  placeSun(centre, size);
}

// Keeps the ground under a travelling creature: the floor moves with it, the grid by whole
// squares (so that its lines stay still and show the motion).
function keepGroundUnder(centre) {
  ground.position.x = centre.x;
  ground.position.z = centre.z;
  if (grid) {
    const step = grid.userData.step || 1;
    grid.position.x = Math.round(centre.x / step) * step;
    grid.position.z = Math.round(centre.z / step) * step;
  }
}

// A walk as the walker task measures D_w (the root's centre, horizontally, from the pose before
// the first measuring frame): that frame (null if none) and the distance at each frame.
function walkOf(frames) {
  const first = frames.findIndex((f) => f.phase === 'measuring');
  if (first < 0) return { start: null, walked: frames.map(() => null) };
  const start = Math.max(0, first - 1);
  const [x0, , z0] = frames[start].parts[0][0];
  const walked = frames.map((f, i) => (i < start ? null : Math.hypot(f.parts[0][0][0] - x0, f.parts[0][0][2] - z0)));
  return { start, walked };
}

function placeSun(centre, size) {
  sun.position.copy(centre).add(new THREE.Vector3(size, size * 2, size * 0.7));
  sun.target.position.copy(centre);
  const cam = sun.shadow.camera;
  cam.left = cam.bottom = -size * 2;
  cam.right = cam.top = size * 2;
  cam.near = 0.01;
  cam.far = size * 8;
  cam.updateProjectionMatrix();
}

function describe(creature, extra) {
  const joints = {};
  for (const j of creature.joints) joints[j.kind] = (joints[j.kind] || 0) + 1;
  const mass = creature.parts.reduce((m, p) => m + p.size[0] * p.size[1] * p.size[2] * p.density, 0);
  const growing = creature.parts.filter((p) => p.growing).length;
  const lines = [
    `parts: ${creature.parts.length}` + (growing ? ` (${growing} growing)` : ''),
    `joints: ${Object.entries(joints).map(([k, n]) => `${n} ${k}`).join(', ') || 'none'}`,
    `neurons: ${creature.brain.neurons.length}   links: ${creature.brain.links.length}`,
    `mass: ${mass.toPrecision(4)} kg`,
  ];
  // A problem met several times in this frame is listed once, with its count.
  const seen = new Map();
  for (const p of creature.problems || []) {
    const line = `${p.severity}: ${p.message}` + (p.module ? ` [${p.module}]` : '');
    seen.set(line, (seen.get(line) || 0) + 1);
  }
  for (const [line, n] of seen) lines.push(n > 1 ? `${line} (${n} times)` : line);
  if (extra) lines.push('', ...extra);
  $('info').textContent = lines.join('\n');
}

// ---------------------------------------------------------------- controls

const slider = $('slider');
const playButton = $('play');
let onFrame = () => {};
let playing = false;
let playTimer = null;

function setFrame(i) {
  const n = Number(slider.max) + 1;
  i = Math.max(0, Math.min(n - 1, Math.round(i)));
  slider.value = String(i);
  body.dataset.frame = String(i);
  onFrame(i);
  requestRender();
}
slider.addEventListener('input', () => setFrame(Number(slider.value)));

function initialFrame(n, fallback) {
  const f = params.get('frame');
  if (f === null) return fallback;
  const k = Number(f);
  if (!Number.isFinite(k)) return fallback;
  return k < 0 ? n + k : k; // frame=-1 is the last
}

function showError(error) {
  const box = $('error');
  if (!error) {
    box.classList.remove('shown');
    delete body.dataset.error;
    $('status').textContent = '';
    return;
  }
  box.textContent = error.text || error.message;
  // A grammar's error keeps its lines (the caret under the column); other messages wrap.
  box.style.whiteSpace = error.location ? 'pre' : 'pre-wrap';
  box.classList.add('shown');
  const where = error.location ? `line ${error.location.line}, column ${error.location.column}: ` : '';
  body.dataset.error = where + error.message;
  $('status').textContent = 'error ' + (error.location ? `at line ${error.location.line}, column ${error.location.column}` : '');
}

// A grammar's findings (located, with the caret) and its builder's problems over all frames
// (each once, with the frames it came up in), beside the creature; none hides the box.
function showFindings(data) {
  const lines = (data.findings || []).map((f) => f.text)
    .concat((data.problems || []).map((p) => p.text));
  $('findings').textContent = lines.join('\n');
  if (lines.length) body.dataset.findings = String(lines.length);
  else delete body.dataset.findings;
}

function finish() {
  document.title = `ontogeny view: ${body.dataset.parts} parts`;
  body.dataset.ready = 'yes';
  requestRender();
}

async function fetchJson(url) {
  const response = await fetch(url, { cache: 'no-store' });
  const value = await response.json();
  if (!response.ok) throw new Error(value.error ? value.error.message : response.statusText);
  return value;
}

// ---------------------------------------------------------------- growth pages

let growthFramed = false;
function showGrowth(data, keepFrame) {
  body.dataset.kind = data.kind;
  $('file').textContent = data.file;
  if (data.defines) showDefines(data.defines, regrowLsys);
  showFindings(data);
  if (data.error) {
    showError(data.error);
    if (!growthFramed) { playButton.style.display = 'none'; slider.style.display = 'none'; }
    finish();
    return;
  }
  showError(null);
  const frames = data.frames;
  const previous = Number(slider.value), wasLast = previous === Number(slider.max);
  slider.max = String(frames.length - 1);
  body.dataset.frames = String(frames.length);
  playButton.style.display = frames.length > 1 ? '' : 'none';
  slider.style.display = frames.length > 1 ? '' : 'none';
  if (!growthFramed || !keepFrame) {
    // Development happens off the ground: draw the ground under the lowest part (as the
    // pictures of `grow --out` do).
    const box = boundsOf(frames.map((f) => f.creature));
    frame(box, Math.min(box.min.y, 0));
    growthFramed = true;
  }
  onFrame = (i) => {
    const f = frames[i];
    drawCreature(f.creature);
    drawBrain(f.creature.brain, f.creature.joints);
    describe(f.creature);
    $('frame-label').textContent = `frame ${i + 1} of ${frames.length}   t = ${+f.t.toFixed(4)}`;
    $('string').textContent = f.string !== null && f.string !== undefined ? f.string
      : (data.kind === 'growth' ? '(grow --out does not store the module strings: view the .lsys file to see them)' : '');
    document.title = `ontogeny view: ${body.dataset.parts} parts`;
  };
  stepPlay = () => setFrame((Number(slider.value) + 1) % frames.length);
  playInterval = 600;
  const start = keepFrame ? (wasLast ? frames.length - 1 : previous) : initialFrame(frames.length, frames.length - 1);
  setFrame(start);
  finish();
}

// Grows the .lsys file again with the values its sliders set.
async function regrowLsys() {
  try {
    showGrowth(await fetchJson('/data.json' + definesQuery()), true);
  } catch (e) {
    showError({ message: e.message });
  }
}

let stepPlay = () => {};
let playInterval = 600;
playButton.addEventListener('click', () => setPlaying(!playing));
function setPlaying(on) {
  // Play from the start again once at the end.
  if (on && !playing && Number(slider.value) === Number(slider.max)) setFrame(0);
  playing = on;
  playButton.textContent = on ? 'pause' : 'play';
  clearInterval(playTimer);
  if (on) playTimer = setInterval(() => stepPlay(), playInterval);
}

// Watch mode: poll the file's fingerprint and reload when it changes.
function watch(kind) {
  if (still) return;
  let version = null;
  const poll = async () => {
    try {
      const v = await (await fetch('/version', { cache: 'no-store' })).text();
      if (version !== null && v !== version) {
        const data = await fetchJson('/data.json' + definesQuery());
        if (kind === 'lsys' || kind === 'growth') showGrowth(data, true);
        $('status').textContent = body.dataset.error ? $('status').textContent : 'reloaded ' + new Date().toLocaleTimeString();
      }
      version = v;
    } catch (e) { /* the server is gone or busy: try again */ }
    setTimeout(poll, 700);
  };
  poll();
}

// ---------------------------------------------------------------- recording pages

// A recorded phase as the GIFs label it (recording.json spells it in kebab case).
function phaseLabel(phase) {
  return { 'controller-on': 'controller on', flying: 'projectile flying' }[phase] || String(phase).replace(/-/g, ' ');
}

// The evaluation's outcome as the recording holds it: status (and message) and fitness.
function outcome(data) {
  const lines = [];
  if (data.status) lines.push(`status: ${data.status}` + (data.message ? ` (${data.message})` : ''));
  if (typeof data.fitness === 'number') {
    lines.push(data.status === 'ok' || !data.status ? `fitness: ${fmt(data.fitness)}` : `fitness: ${data.fitness} (the failure floor)`);
  }
  return lines;
}

// Each frame's part sizes for a growing body: the creature's as dropped, then each frame's
// growth (parts that appear, parts resized) in turn.
function growthSizes(creature, frames) {
  let sizes = creature.parts.map((p) => p.size);
  return frames.map((f) => {
    if (f.growth) {
      sizes = sizes.slice();
      for (const change of f.growth) {
        if (change.appears) sizes[change.appears.part] = change.appears.shape.size;
        else if (change.resized) sizes[change.resized.part] = change.resized.size;
      }
    }
    return sizes;
  });
}

// Plays a recording: a recording page's, or (with `heading`, the lines that name it) the walk of
// a run's individual, shown inside the run page.
function showRecording(data, heading) {
  if (!heading) {
    body.dataset.kind = 'recording';
    $('file').textContent = data.file + (data.task ? `  (${data.task})` : '');
  }
  const named = heading || [];
  const frames = data.frames;
  // A body that grows during the recording (`body`: every part that appears) has a mesh for
  // each of its parts; a frame shows those it poses, at the sizes its growth gives them.
  const meshes = drawCreature(data.body || data.creature);
  const sizesAt = data.body ? growthSizes(data.creature, frames) : null;
  drawBrain(data.creature.brain, data.creature.joints);
  if (!frames.length) {
    // Refused before simulating: the creature as built, and why.
    const box = boundsOf([data.creature]);
    frame(box, Math.min(box.min.y, 0));
    body.dataset.frames = '0';
    playButton.style.display = 'none';
    slider.style.display = 'none';
    describe(data.creature, [...named, `task: ${data.task || '?'}`, ...outcome(data), 'recorded frames: 0 (the starting pose is shown)']);
    $('string').textContent = '';
    showError({ message: data.no_frames || 'no frames recorded' });
    finish();
    return;
  }
  const markers = creatureGroup.children.filter((m) => m.userData.joint);
  playButton.style.display = '';
  slider.style.display = '';
  slider.max = String(frames.length - 1);
  body.dataset.frames = String(frames.length);
  // Frame the first pose; the camera then follows the creature's centre.
  const posed = (f) => ({ parts: data.creature.parts.map((p, i) => ({ ...p, position: f.parts[i][0], orientation: f.parts[i][1] })) });
  const firstBox = boundsOf([posed(frames[0])]);
  const sunSize = firstBox.getSize(new THREE.Vector3()).length();
  const view = firstBox.clone();
  if (Array.isArray(data.target)) view.expandByPoint(v3(data.target));
  frame(view, 0); // the physics' ground: the plane y = 0
  const centreOf = (f) => {
    const c = new THREE.Vector3();
    for (const [p] of f.parts) c.add(v3(p));
    return c.multiplyScalar(1 / Math.max(1, f.parts.length));
  };
  let followed = centreOf(frames[0]);
  // Target, projectile and its trail.
  clearGroup(extrasGroup);
  const scale = typicalSize(data.creature);
  const withProjectile = frames.filter((f) => f.projectile);
  const projectileSize = withProjectile.length
    ? Math.max(...(withProjectile[0].projectile_size || [scale, scale, scale])) : scale;
  if (Array.isArray(data.target)) {
    // A ring on a pole, a few projectiles wide.
    const r = 1.5 * projectileSize;
    const material = new THREE.MeshStandardMaterial({ color: COLORS.target });
    const ring = new THREE.Mesh(new THREE.TorusGeometry(r, r * 0.12, 8, 40), material);
    ring.rotation.x = Math.PI / 2;
    ring.position.copy(v3(data.target));
    extrasGroup.add(ring);
    const height = Math.max(data.target[1], 1e-3);
    const pole = new THREE.Mesh(new THREE.CylinderGeometry(r * 0.06, r * 0.06, height, 8), material);
    pole.position.set(data.target[0], height / 2, data.target[2]);
    extrasGroup.add(pole);
  }
  let projectile = null, trail = null;
  if (withProjectile.length) {
    const size = withProjectile[0].projectile_size || [scale, scale, scale];
    projectile = new THREE.Mesh(new THREE.BoxGeometry(size[0], size[1], size[2]),
      new THREE.MeshStandardMaterial({ color: COLORS.projectile }));
    projectile.castShadow = true;
    extrasGroup.add(projectile);
    const positions = new Float32Array(frames.length * 3);
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));
    trail = new THREE.Line(geometry, new THREE.LineBasicMaterial({ color: COLORS.trail }));
    frames.forEach((f, i) => {
      const p = f.projectile || [NaN, NaN, NaN];
      positions.set(p, i * 3);
    });
    extrasGroup.add(trail);
  }
  // The world: shaped ground, obstacles, objects, water (none for a flat world).
  const objectMeshes = drawWorld(data.scene || { ground: 'level' }, extrasGroup);
  // A walker's walk: the distance so far and the root's path on the ground.
  const walk = data.task === 'walker' ? walkOf(frames) : { start: null, walked: [] };
  let path = null;
  if (walk.start !== null) {
    const positions = new Float32Array(frames.length * 3);
    frames.forEach((f, i) => positions.set([f.parts[0][0][0], 0.002, f.parts[0][0][2]], i * 3));
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));
    path = new THREE.Line(geometry, new THREE.LineBasicMaterial({ color: COLORS.path }));
    extrasGroup.add(path);
  }
  onFrame = (i) => {
    const f = frames[i];
    if (sizesAt) {
      meshes.forEach((m, k) => {
        m.visible = k < f.parts.length;
        const size = sizesAt[i][k];
        if (size) m.scale.set(size[0], size[1], size[2]);
      });
      for (const m of markers) m.visible = m.userData.joint.child < f.parts.length;
      body.dataset.parts = String(f.parts.length);
    }
    f.parts.forEach(([p, q], k) => {
      meshes[k].position.copy(v3(p));
      meshes[k].quaternion.copy(quat(q));
      meshes[k].updateMatrixWorld();
    });
    for (const m of markers) {
      const parent = meshes[m.userData.joint.parent];
      if (parent && m.userData.local) m.position.copy(parent.localToWorld(m.userData.local.clone()));
    }
    (f.objects || []).forEach(([p, q], k) => {
      if (objectMeshes[k]) { objectMeshes[k].position.copy(v3(p)); objectMeshes[k].quaternion.copy(quat(q)); }
    });
    if (projectile) {
      projectile.visible = !!f.projectile;
      if (f.projectile) projectile.position.copy(v3(f.projectile));
      // The trail so far: frames 0..i that had a projectile.
      trail.geometry.setDrawRange(0, i + 1);
    }
    if (path) {
      // The root's path from the walk's start to this frame (nothing before the start).
      path.geometry.setDrawRange(walk.start, Math.max(0, i - walk.start + 1));
    }
    // The camera follows the creature across the ground, not up and down: the ground stays
    // in view whatever the creature does.
    const centre = centreOf(f);
    const delta = centre.clone().sub(followed);
    delta.y = 0;
    camera.position.add(delta);
    if (controls) { controls.target.add(delta); controls.update(); }
    followed.add(delta);
    keepGroundUnder(centre);
    placeSun(centre, sunSize);
    const walked = walk.walked[i];
    $('frame-label').textContent = `frame ${i + 1} of ${frames.length}   t = ${f.t.toFixed(3)} s` +
      (f.phase ? `   ${phaseLabel(f.phase)}` : '') + (walked != null ? `   walked ${walked.toFixed(2)} m` : '');
    body.dataset.walked = walked != null ? walked.toFixed(6) : '';
  };
  const grows = data.body ? [`grows to ${data.body.parts.length} parts during the recording`] : [];
  describe(data.creature, [...named, ...grows, `task: ${data.task || '?'}`, ...outcome(data), `recorded frames: ${frames.length}`,
    `duration: ${frames[frames.length - 1].t.toFixed(2)} s`]);
  $('string').textContent = '';
  // Play at the speed of simulated time.
  const dt = frames.length > 1 ? (frames[frames.length - 1].t - frames[0].t) / (frames.length - 1) : 0.1;
  playInterval = Math.max(16, dt * 1000);
  stepPlay = () => {
    const next = Number(slider.value) + 1;
    if (next >= frames.length) { setPlaying(false); return; }
    setFrame(next);
  };
  setFrame(initialFrame(frames.length, 0));
  finish();
  if (!still && params.get('frame') === null) setPlaying(true);
}

// Leaves a played walk: no player, no target or projectile.
function stopRecording() {
  setPlaying(false);
  playButton.style.display = 'none';
  slider.style.display = 'none';
  $('frame-label').textContent = '';
  clearGroup(extrasGroup);
  onFrame = () => {};
  delete body.dataset.walk;
}

// ---------------------------------------------------------------- run pages

function showRun(data) {
  body.dataset.kind = 'run';
  const algorithm = data.algorithm
    ? `, ${data.algorithm.name}, ${data.algorithm.in_flight} births in flight`
    : '';
  $('file').textContent = `${data.file}  (${data.encoding} on ${data.task}${algorithm})`;
  playButton.style.display = 'none';
  slider.style.display = 'none';
  const rows = [];
  // The plot and the table of generations; called again when the run goes on.
  function listGenerations(generations) {
    drawPlot(generations, data.fitness);
    const table = $('generations');
    table.innerHTML = '<tr><th>gen</th><th>best</th><th>mean</th><th>median</th><th>valid</th></tr>';
    rows.length = 0;
    for (const g of generations) {
      const tr = document.createElement('tr');
      tr.className = 'clickable';
      tr.innerHTML = `<td>${g.index}</td><td>${fmt(g.best)}</td><td>${fmt(g.mean)}</td><td>${fmt(g.median)}</td><td>${g.valid_fraction === null ? '' : Math.round(100 * g.valid_fraction) + '%'}</td>`;
      tr.addEventListener('click', () => openGeneration(g.index, null));
      if (g.index === selectedGeneration) tr.classList.add('selected');
      table.appendChild(tr);
      rows[g.index] = tr;
    }
    body.dataset.generations = String(generations.length);
  }
  let selectedGeneration = null;
  let walkRank = null;
  async function openGeneration(gen, index) {
    rows.forEach((r) => r && r.classList.remove('selected'));
    if (rows[gen]) rows[gen].classList.add('selected');
    selectedGeneration = gen;
    const list = await fetchJson(`/generation.json?gen=${gen}`);
    $('individuals-title').textContent = `Generation ${gen}: individuals, best first`;
    const t = $('individuals');
    t.innerHTML = '<tr><th>rank</th><th>#</th><th>fitness</th><th>status</th><th>parts</th><th></th></tr>';
    const byIndex = [], byRank = [];
    for (const ind of list.individuals) {
      const tr = document.createElement('tr');
      tr.className = 'clickable';
      tr.innerHTML = `<td>${ind.rank}</td><td>${ind.index}</td><td>${fitnessText(ind)}</td><td>${escape(ind.status)}</td><td>${ind.parts}</td>` +
        `<td><button type="button" class="walk" title="evaluate it again and play its ${escape(data.task)}">play</button></td>`;
      tr.addEventListener('click', () => openIndividual(gen, ind, tr));
      tr.querySelector('button.walk').addEventListener('click', (event) => {
        event.stopPropagation();
        playWalk(gen, ind, tr);
      });
      t.appendChild(tr);
      byIndex[ind.index] = [ind, tr];
      byRank[ind.rank] = [ind, tr];
    }
    if (walkRank !== null) {
      // ?walk=R: the walk of rank R, once.
      const rank = walkRank;
      walkRank = null;
      if (byRank[rank]) return playWalk(gen, byRank[rank][0], byRank[rank][1]);
      showError({ message: `generation ${gen} has no rank ${rank} (it has ranks 1 to ${list.individuals.length})` });
      finish();
      return;
    }
    const chosen = index !== null && byIndex[index] ? byIndex[index] : (list.individuals.length ? byIndex[list.individuals[0].index] : null);
    if (chosen) await openIndividual(gen, chosen[0], chosen[1]);
  }
  // The individual shown or being evaluated: an answer for an earlier one is dropped.
  let shown = 0;
  function select(tr) {
    for (const r of $('individuals').querySelectorAll('tr')) r.classList.remove('selected');
    tr.classList.add('selected');
    stopRecording();
    return ++shown;
  }
  const named = (gen, ind) => `generation ${gen}, individual ${ind.index} (rank ${ind.rank})`;
  // Evaluates the individual again with a recording (as replay --gen G --rank R does) and
  // plays it.
  async function playWalk(gen, ind, tr) {
    const request = select(tr);
    showError(null);
    $('status').textContent = `evaluating ${named(gen, ind)}…`;
    $('info').textContent = `${named(gen, ind)}\nevaluating its ${data.task} again, with a recording…`;
    body.dataset.ready = 'no';
    try {
      const walk = await fetchJson(`/walk.json?gen=${gen}&rank=${ind.rank}`);
      if (request !== shown) return;
      $('status').textContent = '';
      const heading = [named(gen, ind)];
      if (walk.habitat !== null && walk.habitat !== undefined) {
        // One trial of one habitat: the run stored the aggregate of all of them.
        heading.push(`in habitat ${walk.habitat}, its first trial`);
        heading.push(`the run stored the aggregate of every habitat and trial: ${walk.stored_fitness}`);
        body.dataset.habitat = walk.habitat;
      } else if (walk.stored_fitness !== walk.fitness) {
        heading.push(`note: the run stored fitness ${walk.stored_fitness}; this evaluation differs`);
      }
      showRecording(walk, heading);
      body.dataset.generation = String(gen);
      body.dataset.individual = String(ind.index);
      body.dataset.walk = `${gen}/${ind.rank}`;
    } catch (e) {
      if (request !== shown) return;
      $('status').textContent = '';
      showError({ message: `${named(gen, ind)}: ${e.message}` });
      finish();
    }
  }
  async function openIndividual(gen, ind, tr) {
    const request = select(tr);
    try {
      const one = await fetchJson(`/individual.json?gen=${gen}&index=${ind.index}`);
      if (request !== shown) return;
      showError(null);
      const c = one.frames[0].creature;
      const box = boundsOf([c]);
      frame(box, Math.min(box.min.y, 0));
      drawCreature(c);
      drawBrain(c.brain, c.joints);
      if (one.habitat) body.dataset.habitat = one.habitat;
      describe(c, [named(gen, ind) + (one.habitat ? `, in habitat ${one.habitat}` : ''), ind.status === 'ok' ? `fitness: ${fmt(ind.fitness)}` : `fitness: ${ind.fitness} (the failure floor)`, `status: ${ind.status}`]);
      body.dataset.generation = String(gen);
      body.dataset.individual = String(ind.index);
    } catch (e) {
      if (request !== shown) return;
      clearGroup(creatureGroup);
      body.dataset.parts = '0';
      showError({ message: `generation ${gen}, individual ${ind.index}: ${e.message}` });
    }
    finish();
  }
  listGenerations(data.generations);
  // A run still going on: new generations join the plot and the table as they are stored.
  if (!still) {
    let version = null;
    const poll = async () => {
      try {
        const v = await (await fetch('/version', { cache: 'no-store' })).text();
        if (version !== null && v !== version) {
          const fresh = await fetchJson('/data.json');
          listGenerations(fresh.generations);
          if (selectedGeneration === null && fresh.generations.length) {
            showError(null);
            openGeneration(fresh.generations[fresh.generations.length - 1].index, null);
          }
        }
        version = v;
      } catch (e) { /* try again */ }
      setTimeout(poll, 2000);
    };
    poll();
  }
  if (!data.generations.length) {
    showError({ message: 'this run has no complete generation yet' });
    finish();
    return;
  }
  const first = data.generations[0].index;
  const last = data.generations[data.generations.length - 1].index;
  const gen = params.has('gen') ? Number(params.get('gen')) : last;
  const index = params.has('index') ? Number(params.get('index')) : null;
  walkRank = params.has('walk') ? Number(params.get('walk')) : null;
  if (!data.generations.some((g) => g.index === gen)) {
    showError({ message: `no generation ${params.get('gen')} (the run has ${first === last ? first : `${first}–${last}`})` });
    finish();
    return;
  }
  openGeneration(gen, index).catch((e) => {
    showError({ message: `generation ${gen}: ${e.message}` });
    finish();
  });
}

function escape(text) {
  const span = document.createElement('span');
  span.textContent = String(text);
  return span.innerHTML;
}

// An individual's fitness as the run table shows it: a failed evaluation scores the failure
// floor, which says nothing the status column does not, so it shows as a dash.
function fitnessText(ind) {
  return ind.status === 'ok' ? fmt(ind.fitness) : '—';
}

function fmt(x) {
  if (x === null || x === undefined) return '';
  const a = Math.abs(x);
  return a !== 0 && (a >= 1e5 || a < 1e-3) ? x.toExponential(2) : (+x.toFixed(3)).toString();
}

// The run's fitness per generation: best and mean, and (dashed, in the best's colour) the best
// re-walked at the fine reference where the run did that, and for a run with habitats or trials
// the band of the best's walks, as fitness.svg draws them; the y axis says what the fitness measures and its unit (`yLabel`).
function drawPlot(generations, yLabel) {
  const canvas = $('plot');
  const g = canvas.getContext('2d');
  const W = canvas.width, H = canvas.height, L = 56, R = 8, T = 10, B = 24;
  g.clearRect(0, 0, W, H);
  const fine = generations.some((x) => x.best_fine !== undefined && x.best_fine !== null);
  body.dataset.plotFine = fine ? 'yes' : 'no';
  body.dataset.plotY = yLabel || '';
  // Failed evaluations score a floor far below the rest: plot what is above it.
  // A run with habitats or trials: the best's walks, lowest to highest, shaded around it.
  const spread = generations.some((x) => x.spread_low !== undefined && x.spread_low !== null);
  body.dataset.plotSpread = spread ? 'yes' : 'no';
  const values = generations.flatMap((x) => [x.best, x.mean, x.best_fine, x.spread_low, x.spread_high]).filter((v) => v !== null && v !== undefined && v > -1e5);
  if (!values.length) return;
  let lo = Math.min(...values), hi = Math.max(...values);
  if (hi - lo < 1e-9) { lo -= 1; hi += 1; }
  const n = Math.max(1, generations.length - 1);
  const X = (i) => L + (W - L - R) * i / n;
  const Y = (v) => T + (H - T - B) * (1 - (v - lo) / (hi - lo));
  g.strokeStyle = '#99a'; g.lineWidth = 1;
  g.beginPath(); g.moveTo(L, T); g.lineTo(L, H - B); g.lineTo(W - R, H - B); g.stroke();
  g.fillStyle = '#556'; g.font = '10px system-ui';
  g.textAlign = 'right'; g.fillText(fmt(hi), L - 3, T + 8); g.fillText(fmt(lo), L - 3, H - B);
  g.textAlign = 'center'; g.fillText('generation', (L + W) / 2, H - 4);
  g.fillText('0', L, H - B + 11); g.fillText(String(generations.length - 1), W - R, H - B + 11);
  if (yLabel) {
    g.save(); g.translate(10, (T + H - B) / 2); g.rotate(-Math.PI / 2);
    g.fillText(yLabel, 0, 0); g.restore();
  }
  const line = (key, color, dashed) => {
    g.strokeStyle = color; g.lineWidth = 2; g.setLineDash(dashed ? [6, 4] : []); g.beginPath();
    let started = false;
    generations.forEach((x, i) => {
      const v = x[key];
      if (v === null || v === undefined || v <= -1e5) { started = false; return; }
      if (started) g.lineTo(X(i), Y(v)); else g.moveTo(X(i), Y(v));
      started = true;
    });
    g.stroke();
    g.setLineDash([]);
  };
  if (spread) {
    // One shaded band per run of generations that have a spread.
    g.fillStyle = 'rgba(0, 114, 178, 0.18)';
    let run = [];
    const shade = () => {
      if (run.length) {
        g.beginPath();
        run.forEach(([i, x], k) => (k ? g.lineTo(X(i), Y(x.spread_high)) : g.moveTo(X(i), Y(x.spread_high))));
        [...run].reverse().forEach(([i, x]) => g.lineTo(X(i), Y(x.spread_low)));
        g.closePath();
        if (run.length === 1) { g.strokeStyle = 'rgba(0, 114, 178, 0.4)'; g.lineWidth = 4; g.stroke(); } else g.fill();
      }
      run = [];
    };
    generations.forEach((x, i) => {
      if (x.spread_low === null || x.spread_low === undefined) shade(); else run.push([i, x]);
    });
    shade();
  }
  line('mean', '#e69f00');
  line('best', '#0072b2');
  if (fine) line('best_fine', '#0072b2', true);
  g.textAlign = 'left';
  g.fillStyle = '#0072b2'; g.fillText('best', L + 6, T + 10);
  g.fillStyle = '#e69f00'; g.fillText('mean', L + 36, T + 10);
  if (fine) { g.fillStyle = '#0072b2'; g.fillText('- - fine reference', L + 70, T + 10); }
  if (spread) { g.fillStyle = '#0072b2'; g.fillText("band: best's walks, lowest to highest", L + 6, T + 22); }
}

// ---------------------------------------------------------------- comparison pages

// A comparison: its replicates on the left (encoding or condition, k, generations stored, best
// and its fine reference), its plots and report where the 3D view would be.
function showComparison(data) {
  body.dataset.kind = 'comparison';
  const names = data.conditions.length ? data.conditions : data.encodings;
  const kind = data.conditions.length ? 'condition' : 'encoding';
  $('file').textContent = `${data.file}  (${names.join(' vs ')}; ${data.fitness})`;
  playButton.style.display = 'none';
  slider.style.display = 'none';
  const rows = data.runs.map((r) => `<tr><td>${r.name}</td><td>${r.k}</td><td>${r.generations}</td><td>${fmt(r.best)}</td><td>${fmt(r.best_fine)}</td></tr>`);
  $('left').innerHTML = `<h2>Replicates</h2><table id="replicates"><tr><th>${kind}</th><th>rep</th><th>gens</th><th>best</th><th>fine ref.</th></tr>` +
    rows.join('') + `</table><p>Each replicate is a run: open one with <code>ontogeny view DIR/${kind.toUpperCase()}/rep-K</code>.</p>`;
  const panel = document.createElement('div');
  panel.id = 'comparison';
  panel.innerHTML = data.plots.map((name) => `<img src="/plot/${name}" alt="${name}">`).join('') + '<pre id="report"></pre>';
  $('scene').appendChild(panel);
  $('report').textContent = data.report === null
    ? 'No report yet: compare writes report.md when its replicates are finished (compare --resume, or compare --merge after --plan).'
    : data.report;
  body.dataset.runs = String(data.runs.length);
  body.dataset.plots = String(data.plots.length);
  document.title = `ontogeny view: comparison of ${names.join(', ')}`;
  body.dataset.ready = 'yes';
}

// ---------------------------------------------------------------- start

resize();
fetchJson('/data.json' + definesQuery()).then((data) => {
  if (data.kind === 'lsys' || data.kind === 'growth') { showGrowth(data, false); watch(data.kind); }
  else if (data.kind === 'recording') showRecording(data);
  else if (data.kind === 'run') showRun(data);
  else if (data.kind === 'comparison') showComparison(data);
  resize();
}).catch((e) => {
  showError({ message: e.message });
  finish();
});
