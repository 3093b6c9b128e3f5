// The three.js view: one mesh, lit, orbitable, drawn only when something
// changed. The camera is fitted to the first mesh of a stream and then left
// alone, so refinements are seen from the same place. It tells when the
// user starts and stops moving the camera, and gives the camera as a
// region request's view in the mesh's own coordinates.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

export class MeshView {
  // Throws an Error when the browser has no WebGL.
  constructor(container) {
    this.container = container;
    this.renderer = createRenderer();
    // No synchronous wait for each shader's compile log: the GPU process
    // compiles while the page goes on.
    this.renderer.debug.checkShaderErrors = false;
    this.renderer.setPixelRatio(window.devicePixelRatio);
    container.appendChild(this.renderer.domElement);
    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color(0xffffff);
    this.camera = new THREE.PerspectiveCamera(40, 1, 0.01, 1000);
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x444455, 1.2));
    const sun = new THREE.DirectionalLight(0xffffff, 1.5);
    sun.position.set(1, 2, 3);
    this.camera.add(sun);  // a light that follows the camera
    this.scene.add(this.camera);
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.addEventListener('change', () => this.draw());
    // OrbitControls says 'start' on a press (and each wheel step), 'end'
    // on its release; what the page does then is its own.
    this.onCameraStart = () => {};
    this.onCameraEnd = () => {};
    this.controls.addEventListener('start', () => this.onCameraStart());
    this.controls.addEventListener('end', () => this.onCameraEnd());
    this.mesh = null;
    new ResizeObserver(() => this.resize()).observe(container);
    this.resize();
    this.compileMaterials();
  }

  // The material of an uncoloured mesh, as setMesh makes it. Compiled here
  // (the GPU process compiles while the decoder loads) and reused by three.js
  // for the first mesh, whose frame then draws without compiling.
  compileMaterials() {
    const probe = new THREE.Mesh(new THREE.BufferGeometry(), meshMaterial(null, null));
    this.scene.add(probe);  // with the scene's lights, which the program depends on
    this.renderer.compile(this.scene, this.camera);
    this.scene.remove(probe);
    probe.geometry.dispose();
    probe.material.dispose();
  }

  resize() {
    const { clientWidth: w, clientHeight: h } = this.container;
    if (!w || !h) return;
    this.renderer.setSize(w, h, false);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.draw();
  }

  // positions: Float32Array xyz; faces: Uint32Array; colors: Float32Array
  // rgb per vertex or null (flat grey); texture: null or {uvs: Float32Array
  // u, v per face corner, image: an ImageBitmap of the base colour map or
  // null while none has arrived} (the decoder's atlas: UVs never travel).
  setMesh(positions, faces, colors, fitCamera, texture = null) {
    const geometry = texture ? cornerGeometry(positions, faces, colors, texture.uvs)
      : indexedGeometry(positions, faces, colors);
    // Flat shading takes the normals from the faces in the shader: the
    // geometry carries none.
    const material = meshMaterial(colors, texture?.image ? this.textureOf(texture.image) : null);
    if (this.mesh) {
      this.scene.remove(this.mesh);
      this.mesh.geometry.dispose();
      this.mesh.material.dispose();
    }
    this.mesh = new THREE.Mesh(geometry, material);
    this.scene.add(this.mesh);
    if (fitCamera) this.fit(geometry);
    this.draw();
  }

  // One GPU texture per image, kept while the image is the one shown.
  textureOf(image) {
    if (this.texture?.image !== image) {
      this.texture?.dispose();
      this.texture = new THREE.Texture(image);
      this.texture.flipY = false;  // glTF's convention: v grows downwards
      this.texture.colorSpace = THREE.SRGBColorSpace;
      this.texture.anisotropy = 4;
      this.texture.needsUpdate = true;
    }
    return this.texture;
  }

  fit(geometry) {
    geometry.computeBoundingSphere();
    const { center, radius } = geometry.boundingSphere;
    const distance = radius / Math.sin(THREE.MathUtils.degToRad(this.camera.fov / 2));
    this.camera.position.copy(center).add(new THREE.Vector3(0.4, 0.3, 1).normalize().multiplyScalar(distance));
    this.camera.near = distance / 100;
    this.camera.far = distance * 10;
    this.camera.updateProjectionMatrix();
    this.controls.target.copy(center);
    this.controls.update();
  }

  // The camera as a view of a region request (ws_protocol.js viewText):
  // eye and look direction in the mesh's own coordinates (its vertices as
  // decoded: the mesh is drawn untransformed today, and the inverse of its
  // world matrix keeps that true if it ever is moved or scaled uniformly),
  // vertical fov in degrees, the canvas's size in pixels. null before the
  // first mesh.
  viewRegion() {
    if (!this.mesh) return null;
    this.mesh.updateMatrixWorld();
    const toMesh = this.mesh.matrixWorld.clone().invert();
    const eye = this.camera.getWorldPosition(new THREE.Vector3()).applyMatrix4(toMesh);
    const direction = this.camera.getWorldDirection(new THREE.Vector3()).transformDirection(toMesh);
    const { width, height } = this.renderer.domElement;
    const pixels = (n) => Math.min(16384, Math.max(1, Math.round(n)));
    return { eye: eye.toArray(), direction: direction.toArray(), fov: this.camera.fov,
             width: pixels(width), height: pixels(height) };
  }

  // Nothing is drawn before the first mesh: with a software renderer an
  // empty frame costs as much as a full one.
  draw() {
    if (this.pending || !this.mesh) return;
    this.pending = true;
    requestAnimationFrame(() => {
      this.pending = false;
      this.renderer.render(this.scene, this.camera);
    });
  }
}

// A WebGL renderer, multisampled unless WebGL runs in software (SwiftShader,
// llvmpipe: a browser without a GPU), where 4x multisampling makes every
// frame several times slower.
function createRenderer() {
  try {
    return new THREE.WebGLRenderer({ antialias: true, failIfMajorPerformanceCaveat: true });
  } catch {
    return new THREE.WebGLRenderer({ antialias: false });
  }
}

// Lambert (diffuse) shading, flat per face: what a mesh preview needs, and
// a shader a software renderer compiles several times faster than the
// physically based one.
function meshMaterial(colors, map) {
  return new THREE.MeshLambertMaterial({
    color: colors || map ? 0xffffff : 0xb8b8c8, vertexColors: !!colors,
    flatShading: true, side: THREE.DoubleSide, map,
  });
}

function indexedGeometry(positions, faces, colors) {
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));
  geometry.setIndex(new THREE.BufferAttribute(faces, 1));
  if (colors) geometry.setAttribute('color', new THREE.BufferAttribute(colors, 3));
  return geometry;
}

// A vertex per face corner: a vertex on a base-mesh edge has a UV per base
// face (the atlas's seams), so the indexed mesh cannot carry them.
function cornerGeometry(positions, faces, colors, uvs) {
  const corners = faces.length;
  const p = new Float32Array(3 * corners);
  const c = colors ? new Float32Array(3 * corners) : null;
  for (let k = 0; k < corners; ++k) {
    const v = 3 * faces[k];
    p[3 * k] = positions[v]; p[3 * k + 1] = positions[v + 1]; p[3 * k + 2] = positions[v + 2];
    if (c) { c[3 * k] = colors[v]; c[3 * k + 1] = colors[v + 1]; c[3 * k + 2] = colors[v + 2]; }
  }
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(p, 3));
  geometry.setAttribute('uv', new THREE.BufferAttribute(uvs, 2));
  if (c) geometry.setAttribute('color', new THREE.BufferAttribute(c, 3));
  return geometry;
}
