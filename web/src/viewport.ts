// One three.js viewport: renderer on its own canvas, camera + OrbitControls, render on demand
// (never a continuous loop: the main thread stays free), click picking of triangles.
import {
  AmbientLight,
  Box3,
  Color,
  DirectionalLight,
  Object3D,
  OrthographicCamera,
  PerspectiveCamera,
  Raycaster,
  Scene,
  Sphere,
  Vector2,
  Vector3,
  WebGLRenderer,
  type Intersection,
} from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';

export interface PickHit {
  object: Object3D;
  faceIndex: number;
}

export class Viewport {
  readonly scene = new Scene();
  readonly renderer: WebGLRenderer;
  readonly camera: PerspectiveCamera | OrthographicCamera;
  readonly controls: OrbitControls;
  /** Objects that can be clicked (triangle meshes). */
  pickable: Object3D[] = [];
  onPick: ((hit: PickHit | null) => void) | undefined;
  private pending = false;
  private waiting: (() => void)[] = [];
  /** Compiled at start-up and never disposed: their shader programs stay (see warmUp). */
  private readonly keepers: Object3D[] = [];
  private readonly raycaster = new Raycaster();

  constructor(readonly container: HTMLElement, readonly mode: '3d' | '2d') {
    // no multisampling on a software GL: SwiftShader runs the fragment work 4x on the CPU, and a
    // remeshed view's frame took 100-165 ms with it against 20-70 ms without (fandisk)
    this.renderer = new WebGLRenderer({ antialias: !softwareGl() });
    this.renderer.setPixelRatio(Math.min(2, window.devicePixelRatio || 1));
    this.renderer.setClearColor(new Color(0x171a20));
    container.appendChild(this.renderer.domElement);
    if (mode === '3d') {
      this.camera = new PerspectiveCamera(35, 1, 0.01, 100);
      this.camera.position.set(1.6, 1.1, 2.2);
      this.scene.add(new AmbientLight(0xffffff, 0.9));
      const key = new DirectionalLight(0xffffff, 1.6);
      key.position.set(1, 2, 3);
      const fill = new DirectionalLight(0xffffff, 0.6);
      fill.position.set(-2, -1, -1.5);
      // lights follow the camera, so the model is lit from the viewer's side
      this.camera.add(key, fill);
      this.scene.add(this.camera);
    } else {
      this.camera = new OrthographicCamera(-1, 1, 1, -1, -10, 10);
      this.camera.position.set(0, 0, 5);
      this.scene.add(new AmbientLight(0xffffff, 3));
    }
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.enableDamping = false;
    if (mode === '2d') {
      this.controls.enableRotate = false;
      this.controls.screenSpacePanning = true;
      this.controls.mouseButtons = { LEFT: 2, MIDDLE: 1, RIGHT: 2 }; // pan with left/right, zoom with wheel
    }
    this.controls.addEventListener('change', () => this.requestRender());
    new ResizeObserver(() => this.resize()).observe(container);
    this.installPicking();
    this.resize();
  }

  /** Render at the next animation frame (coalesced). */
  requestRender(): void {
    if (this.pending) return;
    this.pending = true;
    requestAnimationFrame(() => {
      this.pending = false;
      this.renderer.render(this.scene, this.camera);
      const done = this.waiting;
      this.waiting = [];
      for (const f of done) f();
    });
  }

  /** Resolves once the requested render is drawn (at once when none is pending). */
  drawn(): Promise<void> {
    if (!this.pending) return Promise.resolve();
    return new Promise((resolve) => this.waiting.push(resolve));
  }

  /**
   * Compile the shader programs of `samples` (one object per material kind the view will draw)
   * and keep the samples: three.js frees a program when the last material using it is disposed,
   * and each rebuilt scene would compile it again. The programs compile off the main thread
   * where the browser has KHR_parallel_shader_compile (compileAsync).
   */
  async warmUp(samples: Object3D[]): Promise<void> {
    this.keepers.push(...samples);
    const holder = new Scene();
    for (const o of samples) holder.add(o);
    // with the view's own lights (targetScene): the programs depend on them
    await this.renderer.compileAsync(holder, this.camera, this.scene);
    // and draw them once (in front of the start-up camera): a software GL (SwiftShader) compiles
    // its own rasterizer routines per draw state at the first draw. The samples are gone before
    // the canvas is shown (same task).
    for (const o of samples) this.scene.add(o);
    this.renderer.render(this.scene, this.camera);
    for (const o of samples) this.scene.remove(o);
    this.renderer.render(this.scene, this.camera);
  }

  /** Render now (used before screenshots and after loading). */
  renderNow(): void {
    this.renderer.render(this.scene, this.camera);
  }

  resize(): void {
    const w = Math.max(1, this.container.clientWidth);
    const h = Math.max(1, this.container.clientHeight);
    this.renderer.setSize(w, h, false);
    if (this.camera instanceof PerspectiveCamera) {
      this.camera.aspect = w / h;
    } else {
      const half = (this.camera.top - this.camera.bottom) / 2;
      this.camera.left = (-half * w) / h;
      this.camera.right = (half * w) / h;
    }
    this.camera.updateProjectionMatrix();
    this.requestRender();
  }

  /** Point the camera at `objects` (their union bounding sphere). */
  frame(objects: Object3D[]): void {
    const box = new Box3();
    for (const o of objects) box.expandByObject(o);
    if (box.isEmpty()) return;
    const sphere = box.getBoundingSphere(new Sphere());
    const r = Math.max(sphere.radius, 1e-9);
    this.controls.target.copy(sphere.center);
    if (this.camera instanceof PerspectiveCamera) {
      const dir = new Vector3(0.55, 0.45, 0.7).normalize();
      const vfov = (this.camera.fov * Math.PI) / 180;
      const hfov = 2 * Math.atan(Math.tan(vfov / 2) * this.camera.aspect);
      const dist = r / Math.sin(Math.min(vfov, hfov) / 2);
      this.camera.position.copy(sphere.center).addScaledVector(dir, dist * 1.05);
      this.camera.near = dist / 100;
      this.camera.far = dist * 10;
    } else {
      const w = Math.max(1, this.container.clientWidth), h = Math.max(1, this.container.clientHeight);
      const size = box.getSize(new Vector3());
      const half = 0.53 * Math.max(size.y, (size.x * h) / w);
      this.camera.top = half;
      this.camera.bottom = -half;
      this.camera.left = (-half * w) / h;
      this.camera.right = (half * w) / h;
      this.camera.zoom = 1;
      this.camera.position.set(sphere.center.x, sphere.center.y, 5);
    }
    this.camera.updateProjectionMatrix();
    this.controls.update();
    this.requestRender();
  }

  private installPicking(): void {
    const el = this.renderer.domElement;
    let down: { x: number; y: number } | undefined;
    el.addEventListener('pointerdown', (e) => {
      down = { x: e.clientX, y: e.clientY };
    });
    el.addEventListener('pointerup', (e) => {
      if (!down || Math.hypot(e.clientX - down.x, e.clientY - down.y) > 4) return;
      down = undefined;
      const rect = el.getBoundingClientRect();
      const ndc = new Vector2(((e.clientX - rect.left) / rect.width) * 2 - 1, -((e.clientY - rect.top) / rect.height) * 2 + 1);
      this.raycaster.setFromCamera(ndc, this.camera);
      const hits: Intersection[] = this.raycaster.intersectObjects(this.pickable.filter((o) => o.visible), false);
      const hit = hits.find((h) => h.faceIndex !== undefined && h.faceIndex !== null);
      this.onPick?.(hit ? { object: hit.object, faceIndex: hit.faceIndex! } : null);
    });
  }

  clear(): void {
    for (const child of [...this.scene.children]) {
      if (child === this.camera || child.type.endsWith('Light')) continue;
      this.scene.remove(child);
      disposeTree(child);
    }
    this.pickable = [];
    this.requestRender();
  }
}

let software: boolean | undefined;
/** Whether WebGL runs on a software rasterizer (SwiftShader, llvmpipe), checked once. */
export function softwareGl(): boolean {
  if (software === undefined) {
    const gl = document.createElement('canvas').getContext('webgl2');
    const info = gl?.getExtension('WEBGL_debug_renderer_info');
    const name = gl && info ? String(gl.getParameter(info.UNMASKED_RENDERER_WEBGL)) : '';
    software = /swiftshader|llvmpipe|softpipe|software/i.test(name);
    gl?.getExtension('WEBGL_lose_context')?.loseContext();
  }
  return software;
}

export function disposeTree(o: Object3D): void {
  o.traverse((x) => {
    const g = (x as { geometry?: { dispose(): void } }).geometry;
    g?.dispose();
    const m = (x as { material?: { dispose(): void } | { dispose(): void }[] }).material;
    if (Array.isArray(m)) m.forEach((mm) => mm.dispose());
    else m?.dispose();
  });
}
