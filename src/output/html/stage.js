// The 3-D view: the wall z = 0 (world frame, z up, gravity along −z), the particle placed by an orientation
// (body → world, [w, x, y, z]) and a centre-of-mass position, its centre of mass and contact points marked.
// Drag to orbit, wheel to zoom. One WebGL context per Stage; the poses report renders its thumbnails with one.

class Stage {
  constructor(THREE, canvas, shape, { wallCentre = [0, 0], markers = true } = {}) {
    this.THREE = THREE;
    this.canvas = canvas;
    this.L = shape.length;
    const L = this.L;
    this.renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(1);
    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color(0xf4f6f8);
    this.camera = new THREE.PerspectiveCamera(35, canvas.width / canvas.height, L / 100, L * 200);
    this.camera.up.set(0, 0, 1);
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x667788, 1.6));
    const sun = new THREE.DirectionalLight(0xffffff, 1.8);
    sun.position.set(3 * L, -2 * L, 6 * L);
    this.scene.add(sun);

    // The wall: a square of side 8 L with a grid of L, centred under the particle's start.
    const side = 8 * L;
    const wall = new THREE.Mesh(
      new THREE.PlaneGeometry(side, side),
      new THREE.MeshStandardMaterial({ color: 0xc9ced6, roughness: 0.9, side: THREE.DoubleSide }),
    );
    wall.position.set(wallCentre[0], wallCentre[1], 0);
    this.scene.add(wall);
    const grid = new THREE.GridHelper(side, 8, 0x8a939f, 0xa9b1bb);
    grid.rotation.x = Math.PI / 2;
    grid.position.set(wallCentre[0], wallCentre[1], 1e-4 * L);
    this.scene.add(grid);

    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute("position", new THREE.Float32BufferAttribute(shape.vertices, 3));
    geometry.setIndex(shape.triangles);
    geometry.computeVertexNormals();
    this.body = new THREE.Mesh(
      geometry,
      new THREE.MeshStandardMaterial({ color: 0xd9a441, roughness: 0.55, metalness: 0.05, flatShading: true }),
    );
    this.body.add(
      new THREE.LineSegments(
        new THREE.EdgesGeometry(geometry, 25),
        new THREE.LineBasicMaterial({ color: 0x5a4010, transparent: true, opacity: 0.5 }),
      ),
    );
    this.scene.add(this.body);

    this.hull = shape.hull_vertices;
    this.markerRadius = 0.035 * L;
    const onTop = (colour) => new THREE.MeshBasicMaterial({ color: colour, depthTest: false });
    this.comMarker = new THREE.Mesh(new THREE.SphereGeometry(this.markerRadius, 16, 12), onTop(0x1f4fd1));
    this.comMarker.renderOrder = 2;
    this.comMarker.visible = markers;
    this.scene.add(this.comMarker);
    this.contactGeometry = new THREE.SphereGeometry(this.markerRadius, 12, 8);
    this.contactMaterial = onTop(0xd62728);
    this.contactMarkers = [];

    // The camera orbits a target: azimuth and elevation in radians, distance in L.
    this.view = { azimuth: -0.9, elevation: 0.45, distance: 4 * L, target: new THREE.Vector3(0, 0, 0.4 * L) };
    this.listenForOrbit();
  }

  // Places the particle: q = [w, x, y, z] body → world, com = [x, y, z]; contacts = hull vertex indices.
  setPose(q, com, contacts = []) {
    this.body.quaternion.set(q[1], q[2], q[3], q[0]);
    this.body.position.set(com[0], com[1], com[2]);
    this.comMarker.position.copy(this.body.position);
    while (this.contactMarkers.length < contacts.length) {
      const m = new this.THREE.Mesh(this.contactGeometry, this.contactMaterial);
      m.renderOrder = 2;
      this.scene.add(m);
      this.contactMarkers.push(m);
    }
    this.body.updateMatrixWorld();
    this.contactMarkers.forEach((m, i) => {
      m.visible = i < contacts.length;
      if (!m.visible) return;
      const k = 3 * contacts[i];
      m.position.set(this.hull[k], this.hull[k + 1], this.hull[k + 2]).applyMatrix4(this.body.matrixWorld);
    });
    this.view.target.set(com[0], com[1], Math.max(0.3 * this.L, 0.5 * com[2]));
  }

  render() {
    const { azimuth, elevation, distance, target } = this.view;
    this.camera.position.set(
      target.x + distance * Math.cos(elevation) * Math.cos(azimuth),
      target.y + distance * Math.cos(elevation) * Math.sin(azimuth),
      target.z + distance * Math.sin(elevation),
    );
    this.camera.lookAt(target);
    this.renderer.render(this.scene, this.camera);
  }

  listenForOrbit() {
    let last = null;
    this.canvas.addEventListener("pointerdown", (e) => {
      last = [e.clientX, e.clientY];
      this.canvas.setPointerCapture(e.pointerId);
    });
    this.canvas.addEventListener("pointerup", () => (last = null));
    this.canvas.addEventListener("pointermove", (e) => {
      if (!last) return;
      this.view.azimuth -= 0.01 * (e.clientX - last[0]);
      this.view.elevation = Math.min(1.5, Math.max(-0.1, this.view.elevation + 0.01 * (e.clientY - last[1])));
      last = [e.clientX, e.clientY];
      this.render();
    });
    this.canvas.addEventListener(
      "wheel",
      (e) => {
        e.preventDefault();
        this.view.distance = Math.min(40 * this.L, Math.max(1.5 * this.L, this.view.distance * Math.exp(0.001 * e.deltaY)));
        this.render();
      },
      { passive: false },
    );
  }
}
