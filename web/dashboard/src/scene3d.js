// The 3D view: renders foxglove.SceneUpdate entities (cylinders, cubes, line strips and loops, arrows) and a
// foxglove.PointCloud with three.js, in the map frame (z up), as Foxglove Studio's 3D panel would. Entities
// whose metadata says render=ghost (the simulator's ground truth) are drawn as wireframes over the rest.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { Line2 } from 'three/addons/lines/Line2.js';
import { LineMaterial } from 'three/addons/lines/LineMaterial.js';
import { LineGeometry } from 'three/addons/lines/LineGeometry.js';
import { fromBase64 } from './foxglove.js';

const GHOST_GROWTH = 1.08;
const NUMERIC_SIZE = { 1: 1, 2: 1, 3: 2, 4: 2, 5: 4, 6: 4, 7: 4, 8: 8 };

export class Scene3D {
  constructor(container) {
    this.container = container;
    this.renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(Math.min(window.devicePixelRatio, 2));
    this.renderer.setClearColor(0x14171c);
    container.appendChild(this.renderer.domElement);

    this.scene = new THREE.Scene();
    this.camera = new THREE.PerspectiveCamera(50, 1, 0.1, 2000);
    this.camera.up.set(0, 0, 1);
    this.camera.position.set(-12, -8, 12);
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.target.set(0, 0, 0);
    this.controls.addEventListener('change', () => (this.dirty = true));

    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x445566, 2.2));
    const sun = new THREE.DirectionalLight(0xffffff, 2.0);
    sun.position.set(30, -20, 60);
    this.scene.add(sun);
    const grid = new THREE.GridHelper(400, 80, 0x3a4150, 0x262b33);
    grid.rotation.x = Math.PI / 2;  // the XY plane: the ground in a z-up world
    this.scene.add(grid);
    this.scene.add(new THREE.AxesHelper(2));

    this.entities = new Map();   // "topic entity-id" → { group, expires }
    this.geometries = new Map();
    this.materials = new Map();
    this.box = new THREE.BoxGeometry(1, 1, 1);
    this.points = null;
    this.follow = true;
    this.car = null;
    this.dirty = true;
    this.frames = 0;

    new ResizeObserver(() => this.resize()).observe(container);
    this.resize();
    const loop = () => {
      this.expire();
      if (this.dirty) {
        this.renderer.render(this.scene, this.camera);
        this.frames++;
        this.dirty = false;
      }
      requestAnimationFrame(loop);
    };
    requestAnimationFrame(loop);
  }

  resize() {
    const w = Math.max(1, this.container.clientWidth), h = Math.max(1, this.container.clientHeight);
    this.renderer.setSize(w, h, false);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    for (const { group } of this.entities.values())
      group.traverse((o) => o.material?.resolution?.set(w, h));
    this.dirty = true;
  }

  material(c, ghost = false, outline = false) {
    const key = `${c.r},${c.g},${c.b},${c.a}${ghost ? ',ghost' : ''}${outline ? ',outline' : ''}`;
    let m = this.materials.get(key);
    if (!m && outline) {
      // The body's wires in its own colour (LiDAR-only detections): hollow beside the solid camera-verified ones.
      m = new THREE.MeshBasicMaterial({ color: new THREE.Color(c.r, c.g, c.b), wireframe: true });
      this.materials.set(key, m);
    }
    if (!m && ghost) {
      // A wireframe in a pale version of the colour: it shows where the truth is without hiding what the stack
      // sees, and stays apart from the stack's solid cones where the two agree.
      const pale = new THREE.Color(c.r, c.g, c.b).lerp(new THREE.Color(1, 1, 1), 0.55);
      m = new THREE.MeshBasicMaterial({ color: pale, wireframe: true, transparent: true, opacity: 0.95 });
      this.materials.set(key, m);
    }
    if (!m) {
      // Some emission keeps the cone colours recognisable whatever side the light comes from.
      m = new THREE.MeshStandardMaterial({
        color: new THREE.Color(c.r, c.g, c.b),
        emissive: new THREE.Color(c.r, c.g, c.b).multiplyScalar(0.45),
        transparent: c.a < 1,
        opacity: c.a,
        roughness: 0.6,
        metalness: 0.05,
      });
      this.materials.set(key, m);
    }
    return m;
  }

  cylinderGeometry(bottom, top) {
    const key = `${bottom}|${top}`;
    let g = this.geometries.get(key);
    if (!g) {
      // Unit height and diameter, axis along z (three's cylinders stand along y).
      g = new THREE.CylinderGeometry(0.5 * top, 0.5 * bottom, 1, 20);
      g.rotateX(Math.PI / 2);
      this.geometries.set(key, g);
    }
    return g;
  }

  static place(obj, pose) {
    const p = pose?.position ?? {}, q = pose?.orientation ?? {};
    obj.position.set(p.x ?? 0, p.y ?? 0, p.z ?? 0);
    obj.quaternion.set(q.x ?? 0, q.y ?? 0, q.z ?? 0, q.w ?? 1);
  }

  applySceneUpdate(topic, msg) {
    for (const d of msg.deletions ?? []) {
      for (const key of [...this.entities.keys()])
        if (key.startsWith(`${topic} `) && (d.type === 1 || key === `${topic} ${d.id}`)) this.remove(key);
    }
    for (const e of msg.entities ?? []) {
      const key = `${topic} ${e.id}`;
      this.remove(key);
      const group = new THREE.Group();
      const ghost = (e.metadata ?? []).some((kv) => kv.key === 'render' && kv.value === 'ghost');
      const outline = (e.metadata ?? []).some((kv) => kv.key === 'render' && kv.value === 'outline');
      group.userData = { topic, id: e.id, cylinders: 0, cubes: 0, lines: 0, ghost };
      for (const c of e.cylinders ?? []) {
        const m = new THREE.Mesh(this.cylinderGeometry(c.bottom_scale ?? 1, c.top_scale ?? 1), this.material(c.color, ghost));
        Scene3D.place(m, c.pose);
        const grow = ghost ? GHOST_GROWTH : 1;  // a ghost's wires just outside a solid body at the same place
        m.scale.set(c.size.x * grow, c.size.y * grow, c.size.z * grow);
        group.add(m);
        group.userData.cylinders++;
      }
      for (const c of e.cubes ?? []) {
        const m = new THREE.Mesh(this.box, this.material(c.color, ghost, outline));
        Scene3D.place(m, c.pose);
        m.scale.set(c.size.x, c.size.y, c.size.z);
        group.add(m);
        group.userData.cubes++;
      }
      for (const l of e.lines ?? []) {
        if (!l.points || l.points.length < 2) continue;
        const g = new LineGeometry();
        const pts = l.type === 1 ? [...l.points, l.points[0]] : l.points;  // LINE_LOOP closes
        g.setPositions(pts.flatMap((p) => [p.x, p.y, p.z]));
        const mat = new LineMaterial({
          color: new THREE.Color(l.color.r, l.color.g, l.color.b),
          linewidth: l.thickness || 0.1,
          worldUnits: !l.scale_invariant,
          transparent: l.color.a < 1,
          opacity: l.color.a,
        });
        mat.resolution.set(this.container.clientWidth, this.container.clientHeight);
        const line = new Line2(g, mat);
        line.computeLineDistances();
        Scene3D.place(line, l.pose);
        group.add(line);
        group.userData.lines++;
      }
      for (const a of e.arrows ?? []) {
        const origin = new THREE.Vector3(a.pose.position.x, a.pose.position.y, a.pose.position.z);
        const q = a.pose.orientation;
        const dir = new THREE.Vector3(1, 0, 0).applyQuaternion(new THREE.Quaternion(q.x, q.y, q.z, q.w));
        const len = (a.shaft_length ?? 1) + (a.head_length ?? 0.2);
        group.add(new THREE.ArrowHelper(dir, origin, len, new THREE.Color(a.color.r, a.color.g, a.color.b),
                                        a.head_length ?? 0.2, a.head_diameter ?? 0.1));
      }
      if (ghost) {
        // Drawn over everything: the true car's outline must show through the stack's car box.
        group.traverse((o) => {
          o.renderOrder = 10;
          if (o.material) o.material.depthTest = false;
        });
      }
      const life = e.lifetime ? e.lifetime.sec + e.lifetime.nsec * 1e-9 : 0;
      this.entities.set(key, { group, expires: life > 0 ? performance.now() + life * 1000 : Infinity });
      this.scene.add(group);
    }
    this.dirty = true;
  }

  // Drops every entity of a topic (a subscription turned off).
  removeTopic(topic) {
    for (const key of [...this.entities.keys()]) if (key.startsWith(`${topic} `)) this.remove(key);
  }

  remove(key) {
    const e = this.entities.get(key);
    if (!e) return;
    this.scene.remove(e.group);
    e.group.traverse((o) => {
      if (o.isLine2) {
        o.geometry.dispose();
        o.material.dispose();
      } else if (o.isArrowHelper) {
        o.dispose?.();
      }
    });
    this.entities.delete(key);
    this.dirty = true;
  }

  expire() {
    const now = performance.now();
    for (const [key, e] of this.entities) if (e.expires < now) this.remove(key);
  }

  applyPointCloud(msg) {
    const data = fromBase64(msg.data ?? '');
    const stride = msg.point_stride;
    const fields = Object.fromEntries((msg.fields ?? []).map((f) => [f.name, f]));
    if (!stride || !fields.x || !fields.y) return;
    const n = Math.floor(data.length / stride);
    const view = new DataView(data.buffer, data.byteOffset, data.byteLength);
    const read = (f, off) => {
      if (!f) return 0;
      switch (f.type) {
        case 1: return view.getUint8(off + f.offset);
        case 2: return view.getInt8(off + f.offset);
        case 7: return view.getFloat32(off + f.offset, true);
        case 8: return view.getFloat64(off + f.offset, true);
        default: return NUMERIC_SIZE[f.type] === 2 ? view.getUint16(off + f.offset, true) : view.getUint32(off + f.offset, true);
      }
    };
    const pos = new Float32Array(n * 3), col = new Float32Array(n * 3);
    const c = new THREE.Color();
    for (let i = 0; i < n; i++) {
      const off = i * stride;
      const z = read(fields.z, off);
      pos[3 * i] = read(fields.x, off);
      pos[3 * i + 1] = read(fields.y, off);
      pos[3 * i + 2] = z;
      if (fields.ground && read(fields.ground, off)) c.setRGB(0.35, 0.37, 0.4);
      else c.setHSL(0.55 - Math.min(Math.max(z, -0.5), 1.5) * 0.25, 0.9, 0.6);
      col[3 * i] = c.r;
      col[3 * i + 1] = c.g;
      col[3 * i + 2] = c.b;
    }
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(pos, 3));
    geometry.setAttribute('color', new THREE.BufferAttribute(col, 3));
    if (!this.points) {
      this.points = new THREE.Points(geometry, new THREE.PointsMaterial({ size: 0.07, vertexColors: true }));
      this.scene.add(this.points);
    } else {
      this.points.geometry.dispose();
      this.points.geometry = geometry;
    }
    Scene3D.place(this.points, msg.pose);
    this.pointCount = n;
    this.dirty = true;
  }

  // The car's pose from the vehicle state; the camera follows it when follow is on.
  setCar(x, y) {
    this.car = { x, y };
    if (this.follow) {
      // Keep the camera's offset from its target, and put the target on the car.
      const offset = this.camera.position.clone().sub(this.controls.target);
      this.controls.target.set(x, y, 0);
      this.camera.position.copy(this.controls.target).add(offset);
      this.controls.update();
    }
    this.dirty = true;
  }

  topDown() {
    const t = this.controls.target;
    this.camera.position.set(t.x, t.y - 0.01, 45);
    this.controls.update();
    this.dirty = true;
  }

  // Where the cylinders and cubes of a topic are drawn (the map frame, x/y): for the browser test that checks
  // detection boxes against the truth overlay. Entity groups carry no transform, so a mesh's position is its place.
  positions(topic) {
    const out = [];
    for (const { group } of this.entities.values()) {
      if (group.userData.topic !== topic) continue;
      for (const o of group.children) if (o.isMesh) out.push({ x: o.position.x, y: o.position.y });
    }
    return out;
  }

  // How each detection of a topic is drawn: where (map frame), solid (a box: camera-verified) or hollow (the box's
  // wires: LiDAR only), and in which colour (r, g, b 0..1 as the message gave them); for the browser test.
  detections(topic) {
    const out = [];
    for (const { group } of this.entities.values()) {
      if (group.userData.topic !== topic) continue;
      for (const o of group.children) {
        if (!o.isMesh) continue;
        const c = o.material.color;
        out.push({ x: o.position.x, y: o.position.y, solid: !o.isLine2 && !o.material.wireframe, color: { r: c.r, g: c.g, b: c.b } });
      }
    }
    return out;
  }

  // What is on screen, per topic: for the status line and the browser test.
  counts() {
    const out = {};
    for (const { group } of this.entities.values()) {
      const u = group.userData;
      const t = (out[u.topic] ??= { entities: 0, cylinders: 0, cubes: 0, lines: 0, ghosts: 0 });
      t.entities++;
      if (u.ghost) t.ghosts += u.cylinders + u.cubes + u.lines;
      t.cylinders += u.cylinders;
      t.cubes += u.cubes;
      t.lines += u.lines;
    }
    return { topics: out, points: this.pointCount ?? 0, frames: this.frames };
  }
}
