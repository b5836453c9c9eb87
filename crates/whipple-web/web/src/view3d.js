// The 3-D view of a simulation (three.js): ground with a grid, the four bodies placed by their
// poses from /api/simulate, the rider's centre of mass, contact tracks, a chase camera that the
// user may orbit.
//
// The bicycle is built in the benchmark's axes (x forward, y right, z down) inside one group
// turned +90° about x, which maps them onto three.js's (x, y up, z): (x, y, z) -> (x, -z, y).

import {
  AmbientLight, BufferAttribute, BufferGeometry, Color, CylinderGeometry, DataTexture, DirectionalLight,
  DoubleSide, GridHelper, Group, HemisphereLight, Line, LineBasicMaterial, Matrix4, Mesh, MeshBasicMaterial,
  MeshStandardMaterial, NearestFilter, PerspectiveCamera, CircleGeometry, PlaneGeometry, Quaternion,
  RGBAFormat, Scene, SphereGeometry, TorusGeometry, BoxGeometry, Vector3, WebGLRenderer,
} from "three";
import { OrbitControls } from "three/addons/controls/OrbitControls.js";

const COLOURS = { rider: 0x7c3aed, frame: 0x2563eb, fork: 0xdc2626, tyre: 0x1f2937, spoke: 0x9ca3af, hub: 0x6b7280, rearTrack: 0x374151, frontTrack: 0xdc2626 };
const TRACK_LIFT = -0.002; // tracks drawn just above the ground (z is down)

const v3 = (a) => new Vector3(a[0], a[1], a[2]);

/** A tube of radius `r` from `a` to `b` (benchmark axes), in `material`. */
function tube(a, b, r, material) {
  const d = new Vector3().subVectors(b, a);
  const length = d.length();
  const mesh = new Mesh(new CylinderGeometry(r, r, Math.max(length, 1e-6), 12), material);
  mesh.position.copy(a).addScaledVector(d, 0.5);
  if (length > 0) mesh.quaternion.copy(new Quaternion().setFromUnitVectors(new Vector3(0, 1, 0), d.normalize()));
  return mesh;
}

/** The classic centre-of-mass symbol on a sphere: alternating black and white octants. */
function centreOfMassTexture() {
  const data = new Uint8Array(4 * 2 * 4);
  for (let row = 0; row < 2; row += 1) {
    for (let col = 0; col < 4; col += 1) {
      const v = (row + col) % 2 ? 20 : 250;
      data.set([v, v, v, 255], 4 * (row * 4 + col));
    }
  }
  const texture = new DataTexture(data, 4, 2, RGBAFormat);
  texture.magFilter = NearestFilter;
  texture.minFilter = NearestFilter;
  texture.needsUpdate = true;
  return texture;
}

/** A wheel in its body axes (axle along y): tyre, spokes, hub; a skate (r = 0) is a blade. */
function wheel(radius, colour) {
  const group = new Group();
  if (radius > 1e-3) {
    const tyre = new Mesh(new TorusGeometry(radius, Math.max(0.012, radius * 0.045), 12, 64), new MeshStandardMaterial({ color: COLOURS.tyre, roughness: 0.8 }));
    tyre.rotation.x = Math.PI / 2; // torus axis z -> y
    group.add(tyre);
    const spokeMaterial = new MeshStandardMaterial({ color: colour, roughness: 0.5 });
    for (let k = 0; k < 3; k += 1) {
      const angle = (k * Math.PI) / 3;
      const end = new Vector3(Math.cos(angle) * radius, 0, Math.sin(angle) * radius);
      group.add(tube(end.clone().negate(), end, Math.max(0.004, radius * 0.012), spokeMaterial));
    }
    const rim = new Mesh(new CircleGeometry(radius, 48), new MeshBasicMaterial({ color: colour, transparent: true, opacity: 0.12, side: DoubleSide, depthWrite: false }));
    rim.rotation.x = Math.PI / 2;
    group.add(rim);
  } else {
    group.add(new Mesh(new BoxGeometry(0.16, 0.01, 0.03), new MeshStandardMaterial({ color: COLOURS.tyre })));
  }
  group.add(new Mesh(new SphereGeometry(0.025, 16, 12), new MeshStandardMaterial({ color: COLOURS.hub })));
  return group;
}

/** A growing line on the ground with room for `n` points. */
function track(n, colour) {
  const positions = new Float32Array(3 * Math.max(n, 1));
  const geometry = new BufferGeometry();
  geometry.setAttribute("position", new BufferAttribute(positions, 3));
  geometry.setDrawRange(0, 0);
  return new Line(geometry, new LineBasicMaterial({ color: colour }));
}

export class SimView {
  /** Throws when WebGL is not available. */
  constructor(container) {
    this.container = container;
    this.renderer = new WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(Math.min(2, window.devicePixelRatio || 1));
    this.renderer.domElement.dataset.testid = "sim-canvas";
    container.append(this.renderer.domElement);
    this.scene = new Scene();
    this.scene.background = new Color(0xeaf1f8);
    this.camera = new PerspectiveCamera(45, 1.6, 0.05, 400);
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.enablePan = false;
    this.controls.minDistance = 1;
    this.controls.maxDistance = 40;
    this.controls.maxPolarAngle = Math.PI / 2 - 0.03;
    // The user's orbiting redraws; show() redraws by itself.
    this.controls.addEventListener("change", () => this.following || this.render());

    this.scene.add(new HemisphereLight(0xffffff, 0x8a9a7a, 1.6));
    this.scene.add(new AmbientLight(0xffffff, 0.35));
    const sun = new DirectionalLight(0xffffff, 1.6);
    sun.position.set(-4, 10, -6);
    this.scene.add(sun);

    const ground = new Mesh(new PlaneGeometry(400, 400), new MeshStandardMaterial({ color: 0xdfe7d6, roughness: 1 }));
    ground.rotation.x = -Math.PI / 2;
    this.scene.add(ground);
    this.grid = new GridHelper(60, 60, 0x94a3b8, 0xc5cfbf);
    this.grid.position.y = 0.001;
    this.scene.add(this.grid);

    this.world = new Group(); // benchmark axes
    this.world.rotation.x = Math.PI / 2;
    this.scene.add(this.world);
    this.bodies = [];
    this.resize();
    new ResizeObserver(() => {
      this.resize();
      this.render();
    }).observe(container);
  }

  resize() {
    const w = Math.max(50, this.container.clientWidth);
    const h = Math.max(50, this.container.clientHeight);
    this.renderer.setSize(w, h, false);
    this.renderer.domElement.style.width = "100%";
    this.renderer.domElement.style.height = "100%";
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
  }

  /** Builds the bicycle for a simulation's geometry and tracks for its frames. */
  load(result) {
    for (const child of [...this.world.children]) this.world.remove(child);
    const g = result.geometry;
    const frameMaterial = new MeshStandardMaterial({ color: COLOURS.frame, roughness: 0.45, metalness: 0.1 });
    const forkMaterial = new MeshStandardMaterial({ color: COLOURS.fork, roughness: 0.45, metalness: 0.1 });
    const [rearWheel, rearFrame, frontFrame, frontWheel] = [0, 1, 2, 3].map(() => {
      const group = new Group();
      group.matrixAutoUpdate = false;
      this.world.add(group);
      return group;
    });
    rearWheel.add(wheel(g.rear_wheel_radius, COLOURS.frame));
    frontWheel.add(wheel(g.front_wheel_radius, COLOURS.fork));

    // Rear frame B (origin: the rider's and frame's centre of mass): a triangle between the
    // rear hub, the steer axis and the centre of mass, and the centre-of-mass symbol.
    const hubR = v3(g.rear_hub_in_rear_frame);
    const steerB = v3(g.steer_point_in_rear_frame);
    const axis = v3(g.steer_axis);
    const headLength = Math.max(0.15, 0.35 * Math.max(g.front_wheel_radius, 0.3));
    const headTopB = steerB.clone().addScaledVector(axis, -headLength);
    const cm = new Vector3(0, 0, 0);
    for (const [a, b] of [[hubR, steerB], [hubR, cm], [cm, headTopB], [steerB, headTopB]]) rearFrame.add(tube(a, b, 0.014, frameMaterial));
    const symbol = new Mesh(new SphereGeometry(0.1, 32, 16), new MeshStandardMaterial({ map: centreOfMassTexture(), roughness: 0.6 }));
    // The sphere's poles lie along the body's y axis, so from the side it shows four quadrants.
    symbol.name = "rider-centre-of-mass";
    rearFrame.add(symbol);

    // Front frame H (origin: its centre of mass): fork from the steer axis to the hub, head
    // tube up the steer axis, handlebar across, a small sphere at its centre of mass.
    const steerH = v3(g.steer_point_in_front_frame);
    const hubF = v3(g.front_hub_in_front_frame);
    const topH = steerH.clone().addScaledVector(axis, -headLength);
    frontFrame.add(tube(steerH, hubF, 0.013, forkMaterial));
    frontFrame.add(tube(steerH, topH, 0.017, forkMaterial));
    frontFrame.add(tube(topH.clone().add(new Vector3(0, -0.25, 0)), topH.clone().add(new Vector3(0, 0.25, 0)), 0.012, forkMaterial));
    frontFrame.add(new Mesh(new SphereGeometry(0.035, 16, 12), forkMaterial));

    this.bodies = [rearWheel, rearFrame, frontFrame, frontWheel];
    // The leaning upper body G (origin: its centre of mass): the torso from the hinge through
    // the centre on to the shoulders, a head above, the centre-of-mass symbol; and the hinge
    // line, a short bar along the rear frame's x axis.
    if (g.upper_body) {
      const upper = new Group();
      upper.matrixAutoUpdate = false;
      this.world.add(upper);
      const riderMaterial = new MeshStandardMaterial({ color: COLOURS.rider, roughness: 0.55 });
      const hinge = v3(g.upper_body.hinge_in_upper_body);
      const up = new Vector3().sub(hinge); // from the hinge to the centre
      const length = Math.max(up.length(), 0.05);
      up.normalize();
      // Shoulders about twice as far from the hinge as the centre of mass (a seated torso).
      const shoulders = hinge.clone().addScaledVector(up, 2 * length);
      upper.add(tube(hinge, shoulders, 0.085, riderMaterial));
      const head = new Mesh(new SphereGeometry(0.095, 20, 14), riderMaterial);
      head.position.copy(shoulders.clone().addScaledVector(up, 0.17));
      upper.add(head);
      const gSymbol = new Mesh(new SphereGeometry(0.085, 32, 16), new MeshStandardMaterial({ map: centreOfMassTexture(), roughness: 0.6 }));
      gSymbol.name = "upper-body-centre-of-mass";
      upper.add(gSymbol);
      upper.add(tube(hinge.clone().add(new Vector3(-0.12, 0, 0)), hinge.clone().add(new Vector3(0.12, 0, 0)), 0.02, new MeshStandardMaterial({ color: COLOURS.hub })));
      this.bodies.push(upper);
      symbol.scale.setScalar(0.7); // the rear frame's symbol: the frame and the rider's legs
    }
    this.frames = result.frames;
    this.tracks = [track(this.frames.length, COLOURS.rearTrack), track(this.frames.length, COLOURS.frontTrack)];
    this.frames.forEach((f, i) => {
      this.tracks[0].geometry.attributes.position.setXYZ(i, f.rear_contact[0], f.rear_contact[1], TRACK_LIFT);
      this.tracks[1].geometry.attributes.position.setXYZ(i, f.front_contact[0], f.front_contact[1], TRACK_LIFT);
    });
    for (const t of this.tracks) {
      t.geometry.attributes.position.needsUpdate = true;
      this.world.add(t);
    }
    // A soft shadow under the rider's centre of mass.
    this.shadow = new Mesh(new CircleGeometry(0.25, 32), new MeshBasicMaterial({ color: 0x000000, transparent: true, opacity: 0.12, depthWrite: false }));
    this.world.add(this.shadow);

    // Chase camera: behind, to the left and above the bicycle, looking at the rider.
    const f0 = this.frames[0];
    this.target = this.focus(f0);
    this.controls.target.copy(this.target);
    const yaw = f0.yaw;
    const [back, left, up] = [2.4, 1.7, 1.1];
    const behind = new Vector3(-Math.cos(yaw) * back + Math.sin(yaw) * left, -(Math.sin(yaw) * back + Math.cos(yaw) * left), -up);
    this.camera.position.copy(this.toThree(new Vector3(f0.rear_contact[0], f0.rear_contact[1], 0).add(behind)));
    this.controls.update();
    this.show(0);
  }

  toThree(p) {
    return new Vector3(p.x, -p.z, p.y);
  }

  /** The point the camera looks at: above the middle of the wheelbase, at rider height. */
  focus(f) {
    const x = 0.5 * (f.rear_contact[0] + f.front_contact[0]);
    const y = 0.5 * (f.rear_contact[1] + f.front_contact[1]);
    return this.toThree(new Vector3(x, y, -0.6));
  }

  /** Places the bicycle at frame `i` and moves the camera with it. */
  show(i) {
    const f = this.frames?.[i];
    if (!f) return;
    const m = new Matrix4();
    f.bodies.forEach((pose, k) => {
      const [r0, r1, r2, r3, r4, r5, r6, r7, r8] = pose.rotation;
      const [x, y, z] = pose.position;
      m.set(r0, r1, r2, x, r3, r4, r5, y, r6, r7, r8, z, 0, 0, 0, 1);
      this.bodies[k].matrix.copy(m);
      this.bodies[k].matrixWorldNeedsUpdate = true;
    });
    for (const t of this.tracks) t.geometry.setDrawRange(0, i + 1);
    const rider = f.bodies[1].position;
    this.shadow.position.set(rider[0], rider[1], TRACK_LIFT * 2);
    // Follow: move camera and target by the bicycle's displacement, keeping the user's orbit.
    const target = this.focus(f);
    const shift = target.clone().sub(this.controls.target);
    this.camera.position.add(shift);
    this.controls.target.copy(target);
    this.grid.position.x = Math.round(target.x);
    this.grid.position.z = Math.round(target.z);
    this.following = true;
    this.controls.update();
    this.following = false;
    this.render();
  }

  render() {
    this.renderer.render(this.scene, this.camera);
  }
}
