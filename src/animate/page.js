// The animation page's own script (chaplygin::animate): reads the scene
// embedded in <script id="chaplygin-data" type="application/json">, draws it
// with three.js (the global THREE of the inlined bundle) and exposes
// window.chaplygin (docs/INTERFACE.md, section 10).
//
// World frame: z up, the ground at z = 0, metres. Poses are exact at a
// frame's time (the embedded numbers themselves) and interpolated between
// frames: linearly for positions, by spherical linear interpolation for
// quaternions (x, y, z, w). Rendering is on demand: seek(t) draws at once,
// and playback draws from requestAnimationFrame.
(function () {
  'use strict';

  const data = JSON.parse(document.getElementById('chaplygin-data').textContent);
  const times = Float64Array.from(data.times);
  const frames = times.length;
  const t0 = times[0];
  const tN = times[frames - 1];
  const itemsByName = new Map();
  for (const item of data.items) itemsByName.set(item.name, item);

  // ---- Time and poses ----------------------------------------------------

  // The frame at or before t and the fraction of the way to the next one;
  // fraction 0 at a frame's time exactly and outside [t0, tN] (clamped).
  function locate(t) {
    if (!(t > t0)) return { index: 0, fraction: 0 };
    if (t >= tN) return { index: frames - 1, fraction: 0 };
    let lo = 0;
    let hi = frames - 1; // times[lo] <= t < times[hi]
    while (hi - lo > 1) {
      const mid = (lo + hi) >> 1;
      if (times[mid] <= t) lo = mid;
      else hi = mid;
    }
    if (times[lo] === t) return { index: lo, fraction: 0 };
    return { index: lo, fraction: (t - times[lo]) / (times[lo + 1] - times[lo]) };
  }

  function lerp3(p, i, s) {
    const a = 3 * i;
    const b = a + 3;
    return [
      p[a] + s * (p[b] - p[a]),
      p[a + 1] + s * (p[b + 1] - p[a + 1]),
      p[a + 2] + s * (p[b + 2] - p[a + 2]),
    ];
  }

  // Spherical linear interpolation from quaternion i to i + 1 (the shorter
  // way), normalized; normalized linear interpolation when they nearly agree.
  function slerp(q, i, s) {
    const a = 4 * i;
    const b = a + 4;
    let dot = q[a] * q[b] + q[a + 1] * q[b + 1] + q[a + 2] * q[b + 2] + q[a + 3] * q[b + 3];
    const sign = dot < 0 ? -1 : 1;
    dot *= sign;
    let wa;
    let wb;
    if (dot > 0.9999999) {
      wa = 1 - s;
      wb = s;
    } else {
      const theta = Math.acos(dot);
      const sinTheta = Math.sin(theta);
      wa = Math.sin((1 - s) * theta) / sinTheta;
      wb = Math.sin(s * theta) / sinTheta;
    }
    wb *= sign;
    const r = [0, 1, 2, 3].map((k) => wa * q[a + k] + wb * q[b + k]);
    const norm = Math.hypot(r[0], r[1], r[2], r[3]);
    return r.map((x) => x / norm);
  }

  function poseOf(item, where) {
    const { index, fraction } = where;
    if (fraction === 0) {
      return {
        position: Array.from(item.position.slice(3 * index, 3 * index + 3)),
        quaternion: Array.from(item.quaternion.slice(4 * index, 4 * index + 4)),
      };
    }
    return {
      position: lerp3(item.position, index, fraction),
      quaternion: slerp(item.quaternion, index, fraction),
    };
  }

  function pose(name, t) {
    const item = itemsByName.get(name);
    if (item === undefined) throw new Error('chaplygin.pose: no item named ' + JSON.stringify(name));
    return poseOf(item, locate(Number(t)));
  }

  // ---- The three.js scene ------------------------------------------------

  const view = document.getElementById('view');
  const palette = [0x2f6db5, 0xd9822b, 0x3a9a5b, 0xc0392b, 0x8e5cb5, 0x7f8c8d, 0xb59a2f, 0x2fa5b5];

  function bounds() {
    const min = [Infinity, Infinity, 0];
    const max = [-Infinity, -Infinity, 0];
    const grow = (p) => {
      for (let i = 0; i < p.length; i += 3) {
        for (let k = 0; k < 3; k++) {
          min[k] = Math.min(min[k], p[i + k]);
          max[k] = Math.max(max[k], p[i + k]);
        }
      }
    };
    for (const item of data.items) grow(item.position);
    for (const trace of data.traces) grow(trace.points);
    if (!(min[0] <= max[0])) return { min: [-1, -1, 0], max: [1, 1, 0] };
    return { min, max };
  }

  function itemSize(item) {
    switch (item.shape) {
      case 'disc':
      case 'sphere':
        return 2 * item.radius;
      case 'box':
        return Math.max(...item.size);
      case 'segment':
        return item.length;
      default:
        return 0;
    }
  }

  // A material of the colour `color` mixed two parts to one with white.
  function lightOf(color) {
    const light = new THREE.Color(color).lerp(new THREE.Color(0xffffff), 0.65);
    return new THREE.MeshStandardMaterial({ color: light, roughness: 0.6, metalness: 0.1 });
  }

  function meshOf(item, color) {
    const material = new THREE.MeshStandardMaterial({ color, roughness: 0.6, metalness: 0.1 });
    const dark = new THREE.MeshStandardMaterial({ color: 0x222222, roughness: 0.8 });
    const group = new THREE.Group();
    group.name = item.name;
    switch (item.shape) {
      case 'disc': {
        // CylinderGeometry's axis is its local y axis: the disc's axle.
        const r = item.radius;
        const h = item.thickness;
        group.add(new THREE.Mesh(new THREE.CylinderGeometry(r, r, h, 64), material));
        // A dark spoke along local x and a light quarter between local +z
        // and +x, across both faces, show the disc turning (the quarter
        // tells a half turn from none).
        // Each stands clear of the faces, the spoke of the quarter, by a
        // few hundredths of the thickness.
        group.add(new THREE.Mesh(new THREE.BoxGeometry(1.9 * r, 1.1 * h, 0.12 * r), dark));
        const quarter = new THREE.CylinderGeometry(0.97 * r, 0.97 * r, 1.05 * h, 16, 1, false, 0, Math.PI / 2);
        group.add(new THREE.Mesh(quarter, lightOf(color)));
        break;
      }
      case 'box': {
        const [a, b, c] = item.size;
        group.add(new THREE.Mesh(new THREE.BoxGeometry(a, b, c), material));
        // A dark nose on the +x face marks the heading.
        const nose = new THREE.Mesh(new THREE.BoxGeometry(0.1 * a, 0.3 * b, 1.02 * c), dark);
        nose.position.x = 0.47 * a; // its outer face outside the box's, clear of it
        group.add(nose);
        break;
      }
      case 'sphere': {
        // The eight octants of the local axes in two colours, a
        // checkerboard: a turn about any axis shows. SphereGeometry's phi
        // runs about local y from -x, its theta from +y.
        const r = item.radius;
        const light = lightOf(color);
        for (let octant = 0; octant < 8; octant++) {
          const around = octant % 4;
          const down = octant >> 2;
          const piece = new THREE.SphereGeometry(r, 12, 12, (around * Math.PI) / 2, Math.PI / 2, (down * Math.PI) / 2, Math.PI / 2);
          group.add(new THREE.Mesh(piece, (around + down) % 2 === 0 ? material : light));
        }
        break;
      }
      case 'segment': {
        // A thin rod along the local x axis, centred on the position.
        const rod = new THREE.CylinderGeometry(1, 1, item.length, 12);
        rod.rotateZ(-Math.PI / 2);
        const mesh = new THREE.Mesh(rod, material);
        const thickness = Math.max(0.015 * item.length, 0.005);
        mesh.scale.set(1, thickness, thickness);
        group.add(mesh);
        break;
      }
      default:
        break;
    }
    return group;
  }

  const box = bounds();
  const center = [0, 1, 2].map((k) => (box.min[k] + box.max[k]) / 2);
  const largest = Math.max(0, ...data.items.map(itemSize));
  const extent = Math.max(box.max[0] - box.min[0], box.max[1] - box.min[1], box.max[2] - box.min[2], 2 * largest, 0.5);

  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0xf4f5f7);
  const hemisphere = new THREE.HemisphereLight(0xffffff, 0x8a8a80, 2.2);
  hemisphere.position.set(0, 0, 1);
  scene.add(hemisphere);
  const sun = new THREE.DirectionalLight(0xffffff, 1.6);
  sun.position.set(center[0] + extent, center[1] - 0.7 * extent, 2 * extent);
  scene.add(sun);

  // The ground grid in the plane z = 0 (GridHelper lies in y = 0: turn it).
  // About ten cells across the scene, of 1, 2 or 5 times a power of ten.
  const gridStep = (() => {
    const target = extent / 10;
    const power = Math.pow(10, Math.floor(Math.log10(target)));
    const mantissa = target / power;
    return power * (mantissa < 1.5 ? 1 : mantissa < 3.5 ? 2 : mantissa < 7.5 ? 5 : 10);
  })();
  const gridCells = 2 * Math.ceil((0.75 * extent + largest) / gridStep) + 4;
  const grid = new THREE.GridHelper(gridCells * gridStep, gridCells, 0x9aa0a8, 0xd0d4da);
  grid.rotation.x = Math.PI / 2;
  grid.position.set(Math.round(center[0] / gridStep) * gridStep, Math.round(center[1] / gridStep) * gridStep, 0);
  scene.add(grid);
  const axes = new THREE.AxesHelper(Math.max(gridStep, 0.2 * extent));
  axes.position.z = 1e-4 * extent;
  scene.add(axes);

  const meshes = data.items.map((item, i) => {
    const mesh = meshOf(item, palette[i % palette.length]);
    scene.add(mesh);
    return mesh;
  });

  const traceLines = data.traces.map((trace, i) => {
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(Float32Array.from(trace.points), 3));
    geometry.setDrawRange(0, 1);
    const line = new THREE.Line(geometry, new THREE.LineBasicMaterial({ color: palette[(i + 3) % palette.length] }));
    line.frustumCulled = false;
    scene.add(line);
    return line;
  });

  const camera = new THREE.PerspectiveCamera(45, 1, extent / 1000, extent * 100);
  camera.up.set(0, 0, 1);
  camera.position.set(center[0] + 0.8 * extent, center[1] - 1.1 * extent, center[2] + 0.7 * extent);

  let renderer;
  let controls;
  let failure = null;
  try {
    renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    renderer.setPixelRatio(window.devicePixelRatio || 1);
    view.appendChild(renderer.domElement);
    controls = new THREE.OrbitControls(camera, renderer.domElement);
    controls.target.set(center[0], center[1], center[2]);
    controls.update();
  } catch (error) {
    failure = error;
  }

  // ---- The page's state and drawing ----------------------------------------

  const ui = {
    play: document.getElementById('play'),
    slider: document.getElementById('time'),
    speed: document.getElementById('speed'),
    follow: document.getElementById('follow'),
    clock: document.getElementById('clock'),
    labels: document.getElementById('labels'),
  };
  ui.slider.min = String(t0);
  ui.slider.max = String(tN);

  const labelCells = data.labels.map((label) => {
    const row = document.createElement('tr');
    const name = document.createElement('th');
    name.textContent = label.name;
    const value = document.createElement('td');
    row.append(name, value);
    ui.labels.appendChild(row);
    return value;
  });

  let current = t0;
  let playing = false;
  let anchor = { wall: 0, t: t0 }; // playback: t = anchor.t + speed * (now - anchor.wall)

  function format(x) {
    if (x === 0) return '0';
    const magnitude = Math.abs(x);
    if (magnitude >= 1e-3 && magnitude < 1e6) return x.toFixed(Math.max(0, 5 - Math.floor(Math.log10(magnitude))));
    return x.toExponential(5);
  }

  // Following, the camera keeps its direction to the items' centroid; when
  // the box is first checked it also comes as close as a few times the
  // largest item (the whole run's framing is usually much wider).
  let followed = false;
  function followCentroid() {
    if (!ui.follow.checked || meshes.length === 0 || !controls) {
      followed = false;
      return;
    }
    const c = new THREE.Vector3();
    for (const mesh of meshes) c.add(mesh.position);
    c.divideScalar(meshes.length);
    const offset = camera.position.clone().sub(controls.target);
    if (!followed) offset.setLength(Math.min(offset.length(), 3 * Math.max(largest, 0.25)));
    followed = true;
    camera.position.copy(c).add(offset);
    controls.target.copy(c);
    controls.update();
  }

  function draw() {
    if (!renderer) return;
    const width = view.clientWidth || window.innerWidth;
    const height = view.clientHeight || window.innerHeight;
    const size = renderer.getSize(new THREE.Vector2());
    if (size.x !== width || size.y !== height) {
      renderer.setSize(width, height);
      camera.aspect = width / height;
      camera.updateProjectionMatrix();
    }
    renderer.render(scene, camera);
  }

  function show(t) {
    current = Math.min(Math.max(t, t0), tN);
    const where = locate(current);
    data.items.forEach((item, i) => {
      const p = poseOf(item, where);
      meshes[i].position.set(p.position[0], p.position[1], p.position[2]);
      meshes[i].quaternion.set(p.quaternion[0], p.quaternion[1], p.quaternion[2], p.quaternion[3]);
    });
    for (const line of traceLines) line.geometry.setDrawRange(0, where.index + 1);
    data.labels.forEach((label, i) => {
      labelCells[i].textContent = format(label.values[where.index]);
    });
    ui.clock.textContent = 't = ' + format(current) + ' s';
    ui.slider.value = String(current);
    followCentroid();
    draw();
  }

  function seek(t) {
    const target = Number(t);
    show(Number.isNaN(target) ? current : target);
    anchor = { wall: performance.now(), t: current };
  }

  function speed() {
    return Number(ui.speed.value) || 1;
  }

  function tick(now) {
    if (!playing) return;
    const t = anchor.t + (speed() * (now - anchor.wall)) / 1000;
    if (t >= tN) {
      show(tN);
      pause();
      return;
    }
    show(t);
    requestAnimationFrame(tick);
  }

  function play() {
    if (playing) return;
    if (current >= tN) show(t0);
    playing = true;
    ui.play.textContent = 'Pause';
    anchor = { wall: performance.now(), t: current };
    requestAnimationFrame(tick);
  }

  function pause() {
    playing = false;
    ui.play.textContent = 'Play';
  }

  function step(direction) {
    pause();
    const { index, fraction } = locate(current);
    let next;
    if (direction > 0) next = Math.min(index + 1, frames - 1);
    else next = fraction > 0 ? index : Math.max(index - 1, 0);
    seek(times[next]);
  }

  ui.play.addEventListener('click', () => {
    if (playing) pause();
    else play();
    ui.play.blur(); // so that space reaches the page's handler only
  });
  ui.slider.addEventListener('input', () => seek(Number(ui.slider.value)));
  ui.speed.addEventListener('change', () => {
    anchor = { wall: performance.now(), t: current };
  });
  ui.follow.addEventListener('change', () => show(current));
  window.addEventListener('resize', draw);
  if (controls) controls.addEventListener('change', draw);
  window.addEventListener('keydown', (event) => {
    if (event.target instanceof HTMLSelectElement) return;
    if (event.key === ' ') {
      event.preventDefault();
      if (playing) pause();
      else play();
    } else if (event.key === 'ArrowRight' || event.key === 'ArrowLeft') {
      event.preventDefault();
      step(event.key === 'ArrowRight' ? 1 : -1);
    }
  });

  // ---- window.chaplygin (docs/INTERFACE.md, section 10) -----------------------

  const ready = new Promise((resolve, reject) => {
    if (failure) {
      document.getElementById('failure').textContent = 'WebGL is unavailable: ' + failure.message;
      reject(failure);
      return;
    }
    show(t0);
    resolve();
  });

  window.chaplygin = {
    ready,
    duration: tN - t0,
    times: Float64Array.from(times),
    items: data.items.map((item) => {
      const entry = { name: item.name, shape: item.shape };
      if (item.shape === 'disc') {
        entry.radius = item.radius;
        entry.thickness = item.thickness;
      } else if (item.shape === 'sphere') entry.radius = item.radius;
      else if (item.shape === 'box') entry.size = item.size.slice();
      else if (item.shape === 'segment') entry.length = item.length;
      return entry;
    }),
    pose,
    seek,
    play,
    pause,
  };
})();
