// The report page's 3D view: the avatar and the garments, coloured by distance to the body.
// The scene comes from <script id="gr-scene"> (written by report_page/report_page.cpp):
// meshes quantized and base64-encoded, the heat map's stops and the view's axes. The colour
// rule and the no-fit stripes are those of the still images (page_colours.hpp).
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

// Lights as in the still images: part from all around, the rest from the viewer. three's
// Lambert material divides light by pi (physical units), so a face turned to the viewer
// shows its own colour when the two add up to pi.
const AMBIENT = 0.35 * Math.PI;
const HEADLIGHT = 0.65 * Math.PI;
const SEE_THROUGH_OPACITY = 0.3;
const FIELD_OF_VIEW = 30;

function bytesOf(base64) {
  const text = atob(base64);
  const bytes = new Uint8Array(text.length);
  for (let i = 0; i < text.length; ++i) bytes[i] = text.charCodeAt(i);
  return bytes;
}

// {type: u8|u16|u32, data: base64 of little-endian values} as a typed array.
function decode(entry) {
  const bytes = bytesOf(entry.data);
  if (entry.type === 'u8') return bytes;
  const view = new DataView(bytes.buffer);
  if (entry.type === 'u16') {
    const out = new Uint16Array(bytes.length / 2);
    for (let i = 0; i < out.length; ++i) out[i] = view.getUint16(2 * i, true);
    return out;
  }
  if (entry.type === 'u32') {
    const out = new Uint32Array(bytes.length / 4);
    for (let i = 0; i < out.length; ++i) out[i] = view.getUint32(4 * i, true);
    return out;
  }
  throw new Error(`unknown array type ${entry.type}`);
}

// Positions quantized over their bounding box (mesh_encoding.hpp).
function positionsOf(entry) {
  const q = decode(entry);
  const out = new Float32Array(q.length);
  for (let i = 0; i < q.length; ++i) {
    const axis = i % 3;
    out[i] = entry.min[axis] + (q[i] / 65535) * (entry.max[axis] - entry.min[axis]);
  }
  return out;
}

function valuesOf(entry) {
  const q = decode(entry);
  const out = new Float32Array(q.length);
  for (let i = 0; i < q.length; ++i) out[i] = (q[i] / 65535) * entry.max;
  return out;
}

// The heat map of page_colours.cpp: sRGB stops, linear between them, rounded to bytes.
function heatColour(stops, t) {
  if (!(t < 1)) return stops[stops.length - 1][1];
  t = Math.max(t, 0);
  let i = 1;
  while (stops[i][0] < t) ++i;
  const [p0, c0] = stops[i - 1];
  const [p1, c1] = stops[i];
  const w = (t - p0) / (p1 - p0);
  return [0, 1, 2].map((k) => Math.round((1 - w) * c0[k] + w * c1[k]));
}

function linearColour(rgb) {
  return new THREE.Color().setRGB(rgb[0] / 255, rgb[1] / 255, rgb[2] / 255, THREE.SRGBColorSpace);
}

// Area-weighted vertex normals of an indexed mesh.
function vertexNormals(positions, faces) {
  const normals = new Float32Array(positions.length);
  const a = new THREE.Vector3(), b = new THREE.Vector3(), c = new THREE.Vector3();
  for (let f = 0; f < faces.length; f += 3) {
    a.fromArray(positions, 3 * faces[f]);
    b.fromArray(positions, 3 * faces[f + 1]);
    c.fromArray(positions, 3 * faces[f + 2]);
    b.sub(a);
    c.sub(a);
    b.cross(c);
    for (let k = 0; k < 3; ++k) {
      const v = 3 * faces[f + k];
      normals[v] += b.x;
      normals[v + 1] += b.y;
      normals[v + 2] += b.z;
    }
  }
  for (let v = 0; v < normals.length; v += 3) {
    const length = Math.hypot(normals[v], normals[v + 1], normals[v + 2]);
    if (length > 0) for (let k = 0; k < 3; ++k) normals[v + k] /= length;
  }
  return normals;
}

// A garment: one non-indexed geometry (face colours can differ at a shared vertex) whose
// positions, normals and colours are refilled from the chosen shape.
class GarmentView {
  constructor(entry, scene) {
    this.name = entry.name;
    this.faces = decode(entry.faces);
    this.faceCount = this.faces.length / 3;
    this.noFit = new Uint8Array(this.faceCount);
    for (const f of entry.no_fit) this.noFit[f] = 1;
    this.shapes = entry.shapes.map((s) => {
      const positions = positionsOf(s.positions);
      const marked = new Uint8Array(this.faceCount);
      for (const f of s.marked) marked[f] = 1;
      let ease = null;
      if (s.ease_ratio) {
        ease = valuesOf(s.ease_ratio);
        for (const v of s.ease_unmeasured) ease[v] = NaN;
      }
      return { label: s.label, positions, normals: vertexNormals(positions, this.faces),
               distance: valuesOf(s.distance), marked, ease };
    });
    this.colours = scene.colours;
    this.heatRange = scene.heat_range;
    this.byEase = false;  // colour by the ease kept instead of the distance to the body
    const n = 9 * this.faceCount;
    this.geometry = new THREE.BufferGeometry();
    this.geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(n), 3));
    this.geometry.setAttribute('normal', new THREE.BufferAttribute(new Float32Array(n), 3));
    this.geometry.setAttribute('color', new THREE.BufferAttribute(new Float32Array(n), 3));
    this.geometry.setAttribute('nofit', new THREE.BufferAttribute(new Float32Array(3 * this.faceCount), 1));
    const material = new THREE.MeshLambertMaterial({ vertexColors: true, side: THREE.DoubleSide });
    stripeNoFit(material, scene.colours);
    this.mesh = new THREE.Mesh(this.geometry, material);
    this.shapeIndex = -1;
    this.frameShape = null;  // a frame of the clip, drawn instead of the shapes
    this.drawn = null;
  }

  shapeFor(index) { return this.shapes[Math.min(index, this.shapes.length - 1)]; }

  // The sRGB colour of corner k of face f, as garment_corner_colours decides it.
  cornerColour(shape, f, k) {
    if (shape.marked[f]) return this.colours.marked;
    return this.vertexColour(shape, this.faces[3 * f + k]);
  }

  // The colour of vertex v in the colour mode shown: its distance to the body, or its ease.
  vertexColour(shape, v) {
    if (this.byEase && shape.ease) {
      const ratio = shape.ease[v];
      return Number.isNaN(ratio) ? this.colours.ease_unmeasured
                                 : heatColour(this.colours.ease_stops, ratio / 2);
    }
    return heatColour(this.colours.heat_stops, shape.distance[v] / this.heatRange);
  }

  // Draws shape `index`, or the clip's frame when one is set (setFrame).
  show(index, highlightNoFit) {
    const shape = this.frameShape ?? this.shapeFor(index);
    const position = this.geometry.getAttribute('position');
    const normal = this.geometry.getAttribute('normal');
    const colour = this.geometry.getAttribute('color');
    const noFit = this.geometry.getAttribute('nofit');
    for (let f = 0; f < this.faceCount; ++f)
      for (let k = 0; k < 3; ++k) {
        const corner = 3 * f + k;
        const v = this.faces[corner];
        for (let axis = 0; axis < 3; ++axis) {
          position.array[3 * corner + axis] = shape.positions[3 * v + axis];
          normal.array[3 * corner + axis] = shape.normals[3 * v + axis];
        }
        linearColour(this.cornerColour(shape, f, k)).toArray(colour.array, 3 * corner);
        noFit.array[corner] = highlightNoFit && this.noFit[f] && !shape.marked[f] ? 1 : 0;
      }
    for (const attribute of [position, normal, colour, noFit]) attribute.needsUpdate = true;
    this.geometry.computeBoundingSphere();
    this.geometry.computeBoundingBox();
    this.shapeIndex = index;
    this.drawn = shape;
  }

  // Whether any face around vertex v is drawn in a flag colour instead of the heat map.
  flagged(shape, v) {
    for (let f = 0; f < this.faceCount; ++f)
      for (let k = 0; k < 3; ++k)
        if (this.faces[3 * f + k] === v && (shape.marked[f] || this.noFit[f])) return true;
    return false;
  }
}

// Lays the no-fit stripes of page_colours.hpp over faces whose "nofit" attribute is 1:
// diagonal in screen space, so the heat colour shows between them.
function stripeNoFit(material, colours) {
  const ratio = window.devicePixelRatio;
  const period = (colours.no_fit_stripes.period * ratio).toFixed(3);
  const width = (colours.no_fit_stripes.width * ratio).toFixed(3);
  material.onBeforeCompile = (shader) => {
    shader.uniforms.noFitColour = { value: linearColour(colours.no_fit) };
    const patch = (source, anchor, addition) => {
      if (!source.includes(anchor)) throw new Error(`three's shader has no ${anchor}`);
      return source.replace(anchor, `${anchor}\n${addition}`);
    };
    shader.vertexShader = 'attribute float nofit;\nvarying float vNoFit;\n' +
        patch(shader.vertexShader, '#include <begin_vertex>', 'vNoFit = nofit;');
    shader.fragmentShader = 'uniform vec3 noFitColour;\nvarying float vNoFit;\n' +
        patch(shader.fragmentShader, '#include <color_fragment>',
              `if (vNoFit > 0.5 && mod(gl_FragCoord.x + gl_FragCoord.y, ${period}) < ${width})
                 diffuseColor.rgb = noFitColour;`);
  };
}

// The clip of the page (report_page/page_animation.hpp): every frame's garment positions,
// distances and marked faces, and the avatar's positions at its key frames, between which
// it is interpolated linearly.
class ClipFrames {
  constructor(entry, garments) {
    this.entry = entry;
    this.count = entry.frame_count;
    this.garments = entry.garments.map((g, i) => ({
      view: garments[i],
      positions: positionsOf(g.positions),
      distance: valuesOf(g.distance),
      marked: g.marked,
    }));
    this.avatarKeys = entry.avatar.frames;
    this.avatarPositions = positionsOf(entry.avatar.positions);
    this.avatarSize = this.avatarPositions.length / this.avatarKeys.length;
  }

  // The garment's shape in frame f, in the form GarmentView draws.
  garmentShape(g, f) {
    const { view, positions, distance, marked } = this.garments[g];
    const n = view.shapes[0].positions.length;
    const framePositions = positions.subarray(f * n, (f + 1) * n);
    const flags = new Uint8Array(view.faceCount);
    for (const face of marked[f]) flags[face] = 1;
    return { label: `frame ${f}`, positions: framePositions,
             normals: vertexNormals(framePositions, view.faces),
             distance: distance.subarray((f * n) / 3, ((f + 1) * n) / 3), marked: flags, ease: null };
  }

  // The avatar's positions in frame f: its key frame, or between the two around it.
  avatarAt(f, out) {
    const keys = this.avatarKeys;
    let k = 0;
    while (k + 1 < keys.length && keys[k + 1] <= f) ++k;
    const size = this.avatarSize;
    const a = this.avatarPositions.subarray(k * size, (k + 1) * size);
    if (keys[k] === f || k + 1 === keys.length) {
      out.set(a);
      return;
    }
    const b = this.avatarPositions.subarray((k + 1) * size, (k + 2) * size);
    const w = (f - keys[k]) / (keys[k + 1] - keys[k]);
    for (let i = 0; i < size; ++i) out[i] = (1 - w) * a[i] + w * b[i];
  }

  // "frame 12 of 252, 0.400 s: 3 garment–avatar, 0 self, 0 layer pairs"
  describe(f) {
    const e = this.entry;
    return `frame ${f} of ${this.count}, ${e.times[f].toFixed(3)} s: ` +
        `${e.avatar_pairs[f]} garment–avatar, ${e.self_pairs[f]} self, ${e.layer_pairs[f]} layer pairs`;
  }
}

function avatarMesh(entry, colours) {
  const geometry = new THREE.BufferGeometry();
  const positions = positionsOf(entry.positions);
  geometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));
  geometry.setIndex(new THREE.BufferAttribute(decode(entry.faces), 1));
  geometry.setAttribute('normal', new THREE.BufferAttribute(vertexNormals(positions, geometry.index.array), 3));
  geometry.computeBoundingBox();
  return new THREE.Mesh(geometry, new THREE.MeshLambertMaterial({
    color: linearColour(colours.avatar), side: THREE.DoubleSide }));
}

function start() {
  const scene = JSON.parse(document.getElementById('gr-scene').textContent);
  const box = document.getElementById('gr-view');
  const renderer = new THREE.WebGLRenderer({ antialias: true });
  renderer.setPixelRatio(window.devicePixelRatio);
  renderer.setClearColor(linearColour(scene.colours.background));
  box.appendChild(renderer.domElement);

  const world = new THREE.Scene();
  const avatar = avatarMesh(scene.avatar, scene.colours);
  world.add(avatar);
  const garments = scene.garments.map((g) => new GarmentView(g, scene));
  const shapeCount = Math.max(1, ...garments.map((g) => g.shapes.length));
  let shapeIndex = shapeCount - 1;
  let highlightNoFit = true;
  for (const g of garments) {
    g.show(shapeIndex, highlightNoFit);
    world.add(g.mesh);
  }

  const camera = new THREE.PerspectiveCamera(FIELD_OF_VIEW, 1, 1, 2);
  world.add(camera);
  world.add(new THREE.AmbientLight(0xffffff, AMBIENT));
  const headlight = new THREE.DirectionalLight(0xffffff, HEADLIGHT);
  headlight.position.set(0, 0, 1);  // in camera space: from the viewer
  camera.add(headlight);
  camera.add(headlight.target);

  // Fit everything in view from the front, as the front still shows it.
  const bounds = avatar.geometry.boundingBox.clone();
  for (const g of garments) bounds.union(g.geometry.boundingBox);
  const centre = bounds.getCenter(new THREE.Vector3());
  const radius = Math.max(bounds.getSize(new THREE.Vector3()).length() / 2, 1e-12);
  const up = new THREE.Vector3().fromArray(scene.view.up);
  const front = new THREE.Vector3().fromArray(scene.view.front);
  const distance = (1.1 * radius) / Math.sin(THREE.MathUtils.degToRad(FIELD_OF_VIEW / 2));
  camera.near = distance / 100;
  camera.far = distance * 10;
  camera.up.copy(up);
  const controls = new OrbitControls(camera, renderer.domElement);
  const frontView = () => {
    camera.position.copy(centre).addScaledVector(front, distance);
    controls.target.copy(centre);
    camera.lookAt(centre);
    controls.update();
  };

  const render = () => renderer.render(world, camera);
  let pending = false;
  const requestRender = () => {
    if (pending) return;
    pending = true;
    requestAnimationFrame(() => { pending = false; render(); });
  };
  const resize = () => {
    const width = Math.max(box.clientWidth, 1), height = Math.max(box.clientHeight, 1);
    renderer.setSize(width, height);
    camera.aspect = width / height;
    camera.updateProjectionMatrix();
    render();
  };
  controls.addEventListener('change', requestRender);
  new ResizeObserver(resize).observe(box);
  frontView();
  resize();

  const buttons = [...document.querySelectorAll('.shape-button')];
  // The clip's frame shown, or -1 for the files' pose (the shapes).
  let frame = -1;
  const clip = scene.animation ? new ClipFrames(scene.animation, garments) : null;
  const restAvatar = avatar.geometry.getAttribute('position').array.slice();
  const setShape = (index) => {
    shapeIndex = Math.max(0, Math.min(index, shapeCount - 1));
    for (const g of garments) g.show(shapeIndex, highlightNoFit);
    for (const b of buttons) b.classList.toggle('active', Number(b.dataset.shape) === shapeIndex);
    render();
  };
  for (const b of buttons)
    b.addEventListener('click', () => { play(false); setFrame(-1); setShape(Number(b.dataset.shape)); });
  // Poses the avatar and the garments to frame f of the clip; -1 returns to the files' pose.
  const setFrame = (f) => {
    if (!clip) return;
    frame = f < 0 ? -1 : Math.min(Math.round(f), clip.count - 1);
    const position = avatar.geometry.getAttribute('position');
    if (frame < 0) position.array.set(restAvatar);
    else clip.avatarAt(frame, position.array);
    position.needsUpdate = true;
    const normal = avatar.geometry.getAttribute('normal');
    normal.array.set(vertexNormals(position.array, avatar.geometry.index.array));
    normal.needsUpdate = true;
    avatar.geometry.computeBoundingSphere();
    garments.forEach((g, i) => { g.frameShape = frame < 0 ? null : clip.garmentShape(i, frame); });
    const slider = document.getElementById('gr-frame');
    if (frame >= 0) slider.value = String(frame);
    document.getElementById('gr-frame-info').textContent =
        frame < 0 ? 'pose as given' : clip.describe(frame);
    setShape(shapeIndex);
  };
  let playing = null;  // the interval timer while the clip plays
  const play = (on) => {
    if (!clip || on === (playing !== null)) return;
    const button = document.getElementById('gr-play');
    if (on) {
      if (frame < 0 || frame === clip.count - 1) setFrame(0);
      playing = setInterval(() => setFrame((frame + 1) % clip.count), 1000 / scene.animation.fps);
    } else {
      clearInterval(playing);
      playing = null;
    }
    button.textContent = on ? 'pause' : 'play';
    button.classList.toggle('active', on);
  };
  if (clip) {
    document.getElementById('gr-frame').addEventListener('input', (event) => {
      play(false);
      setFrame(Number(event.target.value));
    });
    document.getElementById('gr-play').addEventListener('click', () => play(playing === null));
    document.getElementById('gr-worst')?.addEventListener('click', (event) => {
      play(false);
      setFrame(Number(event.target.dataset.frame));
    });
    document.getElementById('gr-rest').addEventListener('click', () => {
      play(false);
      setFrame(-1);
    });
    for (const mark of document.querySelectorAll('.frame-marks .mark'))
      mark.addEventListener('click', () => { play(false); setFrame(Number(mark.dataset.frame)); });
  }
  document.addEventListener('keydown', (event) => {
    if (event.key === 't' || event.key === 'T') {
      setFrame(-1);
      setShape((shapeIndex + 1) % shapeCount);
    }
    if (clip && event.key === ' ' && event.target === document.body) {
      event.preventDefault();
      play(playing === null);
    }
  });
  // Only pages with an ease measure have this box.
  document.getElementById('gr-ease')?.addEventListener('change', (event) => {
    for (const g of garments) g.byEase = event.target.checked;
    document.getElementById('gr-legend').hidden = event.target.checked;
    document.getElementById('gr-legend-ease').hidden = !event.target.checked;
    setShape(shapeIndex);
  });
  // Only pages with no-fit faces have this box.
  document.getElementById('gr-nofit')?.addEventListener('change', (event) => {
    highlightNoFit = event.target.checked;
    setShape(shapeIndex);
  });
  // Only outfit pages have a box per garment.
  for (const box of document.querySelectorAll('.garment-toggle')) {
    box.addEventListener('change', (event) => {
      garments[Number(event.target.dataset.garment)].mesh.visible = event.target.checked;
      render();
    });
  }
  document.getElementById('gr-body').addEventListener('change', (event) => {
    avatar.visible = event.target.checked;
    render();
  });
  document.getElementById('gr-seethrough').addEventListener('change', (event) => {
    const material = avatar.material;
    material.transparent = event.target.checked;
    material.opacity = event.target.checked ? SEE_THROUGH_OPACITY : 1;
    material.depthWrite = !event.target.checked;
    material.needsUpdate = true;
    render();
  });
  document.getElementById('gr-reset').addEventListener('click', () => { frontView(); render(); });
  setShape(shapeIndex);

  const raycaster = new THREE.Raycaster();
  // For tests and scripts: the shape shown, and where a garment vertex lands on screen.
  window.grView = {
    shapeCount,
    shape: () => shapeIndex,
    setShape,
    // The clip: its frame count (0 without one), the frame shown (-1: the files' pose),
    // whether it plays, and the frame to show.
    frameCount: clip ? clip.count : 0,
    frame: () => frame,
    playing: () => playing !== null,
    setFrame,
    render,
    vertexCount: (g) => garments[g].shapes[0].positions.length / 3,
    // Page coordinates (CSS pixels) of vertex v of garment g as drawn (the shape or the
    // clip's frame shown), whether it is the nearest surface along its line of sight, and
    // the colour it was given.
    probe(g, v) {
      const garment = garments[g];
      const shape = garment.drawn;
      const point = new THREE.Vector3().fromArray(shape.positions, 3 * v);
      const ndc = point.clone().project(camera);
      const rect = renderer.domElement.getBoundingClientRect();
      const x = rect.left + ((ndc.x + 1) / 2) * rect.width;
      const y = rect.top + ((1 - ndc.y) / 2) * rect.height;
      raycaster.set(camera.position, point.clone().sub(camera.position).normalize());
      const visibleMeshes = [avatar, ...garments.map((m) => m.mesh)].filter((m) => m.visible);
      const hit = raycaster.intersectObjects(visibleMeshes, false)[0];
      const reach = camera.position.distanceTo(point);
      const visible = Math.abs(ndc.x) < 1 && Math.abs(ndc.y) < 1 && hit !== undefined &&
          hit.object === garment.mesh && Math.abs(hit.distance - reach) < 1e-3 * radius;
      const colour = garment.vertexColour(shape, v);
      return { x, y, visible, colour, flagged: garment.flagged(shape, v) };
    },
  };
}

try {
  start();
} catch (error) {
  const box = document.getElementById('gr-view');
  if (box) box.innerHTML = '<p class="error">The 3D view could not start: ' +
      String(error.message).replace(/[<&]/g, '') + '</p>';
  console.error('report view:', error);
}
