// robodesc view: draws the scene data robodesc embedded in this page (robodesc/view/scene.py) with
// three.js (the THREE global of the vendored bundle). Nothing is fetched: meshes are GLB in base64.
//
// Frames follow URDF: each joint is parent link -> joint frame (origin xyz, fixed-axis rpy) ->
// motion (rotation about / translation along the axis) -> child link. Z is up.
// window.robodesc is the page's small API, used by the browser tests and handy in the console.
(function () {
  'use strict';

  const data = JSON.parse(document.getElementById('robodesc-data').textContent);
  const api = (window.robodesc = { ready: false, data: data, highlighted: null, errors: [] });
  window.addEventListener('error', (e) => api.errors.push(String(e.message)));

  // ---- renderer, camera, lights ------------------------------------------------------------
  const host = document.getElementById('view');
  let renderer;
  try {
    renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  } catch (err) {
    // No WebGL (disabled, or no GPU and no software fallback): say so instead of a blank page.
    host.textContent = 'This browser cannot draw WebGL here (' + err.message + '). Open the page in a browser with WebGL.';
    host.className = 'nogl';
    api.errors.push(String(err.message));
    return;
  }
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  host.appendChild(renderer.domElement);
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0xeef0f3);
  const camera = new THREE.PerspectiveCamera(40, 1, 0.001, 1000);
  camera.up.set(0, 0, 1);
  const controls = new THREE.OrbitControls(camera, renderer.domElement);
  controls.addEventListener('change', requestRender);
  scene.add(new THREE.HemisphereLight(0xffffff, 0x8a8f99, 2.0));
  const headlight = new THREE.DirectionalLight(0xffffff, 1.6);
  headlight.position.set(0.3, 0.6, 1);
  camera.add(headlight); // a light from the viewer's side: every face the camera sees is lit
  scene.add(camera);

  let pending = false;
  function requestRender() {
    if (pending) return;
    pending = true;
    requestAnimationFrame(() => {
      pending = false;
      renderNow();
    });
  }
  function renderNow() {
    if (highlightBox && api.highlighted) updateHighlightBox();
    renderer.render(scene, camera);
  }
  function resize() {
    const w = Math.max(1, host.clientWidth), h = Math.max(1, host.clientHeight);
    renderer.setSize(w, h, false);
    camera.aspect = w / h;
    camera.updateProjectionMatrix();
    requestRender();
  }
  window.addEventListener('resize', resize);

  // ---- helpers -----------------------------------------------------------------------------
  function setPose(obj, p) {
    obj.position.set(p.xyz[0], p.xyz[1], p.xyz[2]);
    // URDF's fixed-axis roll-pitch-yaw is R = Rz(yaw) Ry(pitch) Rx(roll): three.js's 'ZYX' order.
    obj.rotation.set(p.rpy[0], p.rpy[1], p.rpy[2], 'ZYX');
  }
  function el(tag, cls, text) {
    const e = document.createElement(tag);
    if (cls) e.className = cls;
    if (text !== undefined) e.textContent = text;
    return e;
  }
  function base64Buffer(text) {
    const raw = atob(text);
    const bytes = new Uint8Array(raw.length);
    for (let i = 0; i < raw.length; i++) bytes[i] = raw.charCodeAt(i);
    return bytes.buffer;
  }
  // Meshes are gzipped GLB in base64: inflated by the browser's own DecompressionStream.
  function inflate(buffer) {
    const stream = new Blob([buffer]).stream().pipeThrough(new DecompressionStream('gzip'));
    return new Response(stream).arrayBuffer();
  }
  async function parseGlb(text) {
    if (text === null) return null;
    const buffer = await inflate(base64Buffer(text));
    const loader = new THREE.GLTFLoader();
    return new Promise((resolve) => {
      loader.parse(buffer, '', (gltf) => {
        let geometry = null;
        gltf.scene.traverse((o) => { if (o.isMesh && !geometry) geometry = o.geometry; });
        resolve(geometry);
      }, () => resolve(null));
    });
  }

  // ---- the robot ---------------------------------------------------------------------------
  const links = {}; // name -> {group, own: Group of its shapes, materials: [], data}
  const jointObjs = {}; // name -> {data, motion, axis: Vector3}
  const layers = { visual: [], collision: [], frames: [], axes: [], com: [], inertia: [] };
  const robotRoot = new THREE.Group();
  scene.add(robotRoot);

  function primitive(s) {
    let g;
    if (s.kind === 'box') g = new THREE.BoxGeometry(s.size[0], s.size[1], s.size[2]);
    else if (s.kind === 'sphere') g = new THREE.SphereGeometry(s.radius, 32, 16);
    else if (s.kind === 'cylinder') g = new THREE.CylinderGeometry(s.radius, s.radius, s.length, 32).rotateX(Math.PI / 2);
    else if (s.kind === 'capsule') g = new THREE.CapsuleGeometry(s.radius, s.length, 8, 24).rotateX(Math.PI / 2);
    return g;
  }

  function shapeMesh(s, geometries, collider) {
    let geometry = s.kind === 'mesh' ? geometries[s.mesh] : primitive(s);
    if (!geometry) {
      // A mesh whose file is missing or unreadable: a red marker where it would be.
      const marker = new THREE.Mesh(new THREE.OctahedronGeometry(0.02),
        new THREE.MeshBasicMaterial({ color: 0xd02020, wireframe: true }));
      setPose(marker, s);
      marker.userData.marker = true;
      return marker;
    }
    const rgba = s.rgba;
    const material = new THREE.MeshStandardMaterial({
      color: new THREE.Color(rgba[0], rgba[1], rgba[2]),
      opacity: rgba[3], transparent: rgba[3] < 1, depthWrite: !collider && rgba[3] >= 1,
      flatShading: s.kind === 'mesh', roughness: 0.75, metalness: 0.05,
      // CAD exports often wind some faces the wrong way: draw both sides.
      side: THREE.DoubleSide,
    });
    const mesh = new THREE.Mesh(geometry, material);
    setPose(mesh, s);
    return mesh;
  }

  function buildRobot(geometries) {
    for (const link of data.links) {
      const group = new THREE.Group();
      group.name = link.name;
      const own = new THREE.Group();
      group.add(own);
      const visual = new THREE.Group(), collision = new THREE.Group();
      own.add(visual, collision);
      const materials = [];
      for (const s of link.visuals) visual.add(shapeMesh(s, geometries, false));
      for (const s of link.collisions) collision.add(shapeMesh(s, geometries, true));
      own.traverse((o) => { if (o.isMesh && !o.userData.marker) materials.push(o.material); });
      layers.visual.push(visual);
      layers.collision.push(collision);
      links[link.name] = { group, own, visual, collision, materials, data: link };
    }
    for (const j of data.joints) {
      const frame = new THREE.Group();
      setPose(frame, j);
      const motion = new THREE.Group();
      frame.add(motion);
      motion.add(links[j.child].group);
      links[j.parent].group.add(frame);
      const axis = new THREE.Vector3(j.axis[0], j.axis[1], j.axis[2]);
      if (axis.lengthSq() > 0) axis.normalize();
      jointObjs[j.name] = { data: j, frame, motion, axis };
    }
    for (const r of data.roots) robotRoot.add(links[r].group);
  }

  // The world the robot stands in (--world, --terrain): its ground, and the robot at its spawn
  // (the first copy; the page's sliders move one robot).
  function buildWorld(geometries) {
    if (!data.world) return;
    const ground = new THREE.Group();
    ground.name = 'world';
    for (const s of data.world.ground) ground.add(shapeMesh(s, geometries, false));
    scene.add(ground);
    api.groundShapes = ground.children.length;
    if (data.world.robots.length) setPose(robotRoot, data.world.robots[0]);
  }

  // Frames, axes, centres of mass and inertia boxes are sized from the robot's own size.
  function buildHelpers(size) {
    const s = Math.max(size, 1e-3);
    for (const name in links) {
      const link = links[name];
      const axes = new THREE.AxesHelper(0.06 * s);
      link.group.add(axes);
      layers.frames.push(axes);
      const inertial = link.data.inertial;
      if (inertial) {
        const frame = new THREE.Group();
        setPose(frame, inertial);
        link.own.add(frame);
        const com = new THREE.Mesh(new THREE.SphereGeometry(0.012 * s, 16, 8),
          new THREE.MeshBasicMaterial({ color: 0x111111 }));
        frame.add(com);
        layers.com.push(com);
        if (inertial.box) {
          const box = inertiaBox(inertial, 0x2060d0);
          frame.add(box);
          layers.inertia.push(box);
        }
      }
    }
    for (const name in jointObjs) {
      const j = jointObjs[name];
      if (!j.data.range || j.axis.lengthSq() === 0) continue;
      const arrow = new THREE.ArrowHelper(j.axis, new THREE.Vector3(), 0.2 * s, 0xc02090, 0.04 * s, 0.02 * s);
      j.frame.add(arrow);
      layers.axes.push(arrow);
    }
  }

  function inertiaBox(inertial, color) {
    const b = inertial.box;
    const geo = new THREE.EdgesGeometry(new THREE.BoxGeometry(Math.max(b[0], 1e-5), Math.max(b[1], 1e-5), Math.max(b[2], 1e-5)));
    const box = new THREE.LineSegments(geo, new THREE.LineBasicMaterial({ color }));
    const q = inertial.quat; // w, x, y, z
    box.quaternion.set(q[1], q[2], q[3], q[0]);
    return box;
  }

  // ---- joints ------------------------------------------------------------------------------
  const q = {};
  const sliders = {};
  function jointValue(name, depth) {
    const j = jointObjs[name];
    if (!j) return 0;
    const m = j.data.mimic;
    if (m && depth < 64) return m.multiplier * jointValue(m.joint, depth + 1) + m.offset;
    return name in q ? q[name] : j.data.home;
  }
  function applyPose() {
    for (const name in jointObjs) {
      const j = jointObjs[name];
      if (!j.data.range) continue;
      const v = jointValue(name, 0);
      if (j.data.type === 'prismatic') {
        j.motion.position.copy(j.axis).multiplyScalar(v);
      } else {
        j.motion.quaternion.setFromAxisAngle(j.axis, v);
      }
      const slider = sliders[name];
      if (slider) {
        if (j.data.mimic) slider.input.value = String(v);
        slider.value.textContent = v.toFixed(3);
      }
    }
    requestRender();
  }
  function setJoint(name, value) {
    const j = jointObjs[name];
    if (!j || !j.data.range || j.data.mimic) return false;
    q[name] = Math.min(Math.max(value, j.data.range[0]), j.data.range[1]);
    sliders[name].input.value = String(q[name]);
    applyPose();
    return true;
  }

  function buildSliders() {
    const box = document.getElementById('joints');
    let count = 0;
    for (const j of data.joints) {
      if (!j.range) continue;
      count++;
      const row = el('div', 'joint' + (j.mimic ? ' mimic' : ''));
      row.dataset.joint = j.name;
      const name = el('span', 'name', j.name + (j.mimic ? ' = ' + j.mimic.multiplier + '·' + j.mimic.joint + (j.mimic.offset ? ' + ' + j.mimic.offset : '') : ''));
      name.title = j.type + ', ' + j.parent + ' → ' + j.child + ' [' + j.range[0].toFixed(3) + ', ' + j.range[1].toFixed(3) + ']';
      name.addEventListener('click', () => select(j.child));
      const value = el('span', 'value', j.home.toFixed(3));
      const input = el('input');
      input.type = 'range';
      input.min = String(j.range[0]);
      input.max = String(j.range[1]);
      input.step = String((j.range[1] - j.range[0]) / 1000 || 0.001);
      input.value = String(j.home);
      input.id = 'joint-' + j.name;
      input.disabled = !!j.mimic; // a mimic joint follows its leader
      input.addEventListener('input', () => { q[j.name] = parseFloat(input.value); applyPose(); });
      row.append(name, value, input);
      box.appendChild(row);
      sliders[j.name] = { input, value };
    }
    document.getElementById('joints-count').textContent = String(count);
    if (!count) box.appendChild(el('div', 'empty', 'no joint that moves'));
  }

  // ---- selection ---------------------------------------------------------------------------
  let highlightBox = null;
  const HIGHLIGHT = new THREE.Color(0xff6a00);
  const ghosts = new THREE.Group();
  function updateHighlightBox() {
    const link = links[api.highlighted];
    const bounds = new THREE.Box3();
    link.own.updateWorldMatrix(true, true);
    bounds.setFromObject(link.visual.children.length ? link.visual : link.own);
    if (bounds.isEmpty()) {
      const p = new THREE.Vector3().setFromMatrixPosition(link.group.matrixWorld);
      bounds.setFromCenterAndSize(p, new THREE.Vector3(0.02, 0.02, 0.02).multiplyScalar(Math.max(robotSize, 0.1) * 4));
    }
    highlightBox.box.copy(bounds);
  }
  function select(name, ghost) {
    for (const m of Object.values(links)) for (const mat of m.materials) mat.emissive.setRGB(0, 0, 0);
    ghosts.clear();
    document.querySelectorAll('.active').forEach((e) => e.classList.remove('active'));
    const link = links[name];
    api.highlighted = link ? name : null;
    if (!highlightBox) {
      highlightBox = new THREE.Box3Helper(new THREE.Box3(), 0xff6a00);
      scene.add(highlightBox, ghosts);
    }
    highlightBox.visible = !!link;
    document.getElementById('selection').textContent = link ? 'link ' + name : '';
    if (link) {
      for (const mat of link.materials) mat.emissive.copy(HIGHLIGHT).multiplyScalar(0.55);
      const item = document.querySelector('.tree .link[data-link="' + CSS.escape(name) + '"]');
      if (item) item.classList.add('active');
      if (ghost) {
        // Inertia before (red) and after (green), in the link's frame.
        link.group.add(ghosts);
        for (const [inertial, color] of [[ghost.before_box, 0xd02020], [ghost.after_box, 0x17a040]]) {
          if (!inertial || !inertial.box) continue;
          const frame = new THREE.Group();
          setPose(frame, inertial);
          frame.add(inertiaBox(inertial, color));
          ghosts.add(frame);
        }
      }
    }
    requestRender();
    return !!link;
  }

  // ---- panels ------------------------------------------------------------------------------
  function buildTree() {
    const byParent = {};
    for (const j of data.joints) (byParent[j.parent] = byParent[j.parent] || []).push(j);
    const flagged = new Set(data.findings.filter((f) => f.link && f.severity !== 'info').map((f) => f.link));
    function item(linkName, via) {
      const li = el('li');
      if (via) li.appendChild(el('span', 'via', via.name + ' (' + via.type + ') → '));
      const span = el('span', 'link', linkName);
      span.dataset.link = linkName;
      span.addEventListener('click', () => select(linkName));
      li.appendChild(span);
      if (flagged.has(linkName)) li.appendChild(el('span', 'flag', ' !'));
      const kids = byParent[linkName] || [];
      if (kids.length) {
        const ul = el('ul');
        for (const j of kids) ul.appendChild(item(j.child, j));
        li.appendChild(ul);
      }
      return li;
    }
    const tree = document.getElementById('tree');
    for (const r of data.roots) tree.appendChild(item(r, null));
  }

  function buildFindings() {
    const list = document.getElementById('findings');
    document.getElementById('findings-count').textContent = String(data.findings.length);
    if (!data.findings.length) list.appendChild(el('li', 'empty', 'none'));
    data.findings.forEach((f, i) => {
      const li = el('li', f.severity + (f.link ? ' linked' : ''));
      li.id = 'finding-' + i;
      if (f.link) li.dataset.link = f.link;
      li.append(el('span', 'code', f.severity + ' ' + f.code + ' '));
      if (f.element) li.append(el('span', 'element', f.element + ': '));
      li.append(document.createTextNode(f.message));
      if (f.where) li.title = f.where;
      if (f.link) li.addEventListener('click', () => { select(f.link); li.classList.add('active'); });
      list.appendChild(li);
    });
  }

  function buildRepairs() {
    const box = document.getElementById('repairs');
    document.getElementById('repairs-count').textContent = String(data.repairs.length);
    if (!data.repairs.length) {
      box.appendChild(el('div', 'empty', data.target ? 'the passes changed no link' : 'shown with --target (the robot after its passes)'));
    }
    data.repairs.forEach((r, i) => {
      const div = el('div', 'repair');
      div.id = 'repair-' + i;
      div.dataset.link = r.link;
      div.append(el('span', 'kind', r.kind + ' '), el('span', '', r.link));
      const table = el('table');
      for (const [label, text] of [['before', r.before], ['after', r.after]]) {
        const tr = el('tr', label);
        tr.append(el('td', 'label', label), el('td', 'value', text));
        table.appendChild(tr);
      }
      div.appendChild(table);
      div.addEventListener('click', () => { select(r.link, r.kind === 'inertia' ? r : null); div.classList.add('active'); });
      box.appendChild(div);
    });
  }

  function bindToggles() {
    // A robot drawn by its colliders alone (no visual anywhere) starts with them shown.
    if (!data.links.some((l) => l.visuals.length)) document.getElementById('toggle-collision').checked = true;
    for (const name of Object.keys(layers)) {
      const box = document.getElementById('toggle-' + name);
      const apply = () => { for (const o of layers[name]) o.visible = box.checked; requestRender(); };
      box.addEventListener('change', apply);
      apply();
    }
  }

  // ---- framing -----------------------------------------------------------------------------
  let robotSize = 1;
  const center = new THREE.Vector3();
  function bounds() {
    robotRoot.updateWorldMatrix(true, true);
    const b = new THREE.Box3();
    for (const layer of [layers.visual, layers.collision]) for (const g of layer) b.expandByObject(g);
    if (b.isEmpty()) b.setFromCenterAndSize(new THREE.Vector3(), new THREE.Vector3(0.5, 0.5, 0.5));
    return b;
  }
  function frame() {
    const b = bounds();
    b.getCenter(center);
    const sphere = b.getBoundingSphere(new THREE.Sphere());
    const r = Math.max(sphere.radius, 0.05);
    const dist = r / Math.sin((camera.fov * Math.PI) / 360) * 1.05;
    const dir = new THREE.Vector3(1.0, -0.9, 0.65).normalize();
    camera.position.copy(center).addScaledVector(dir, dist);
    camera.near = dist / 100;
    camera.far = dist * 100;
    camera.updateProjectionMatrix();
    controls.target.copy(center);
    controls.update();
    requestRender();
  }

  // Screen position (CSS pixels in the canvas) of a link's own shapes: for tests and tools.
  api.project = function (name) {
    const link = links[name];
    if (!link) return null;
    robotRoot.updateWorldMatrix(true, true);
    const b = new THREE.Box3().setFromObject(link.own);
    const p = b.isEmpty() ? new THREE.Vector3().setFromMatrixPosition(link.group.matrixWorld) : b.getCenter(new THREE.Vector3());
    p.project(camera);
    const c = renderer.domElement;
    return { x: (p.x + 1) / 2 * c.clientWidth, y: (1 - p.y) / 2 * c.clientHeight };
  };
  api.setJoint = setJoint;
  api.select = select;
  api.renderNow = renderNow;
  api.jointValue = (name) => jointValue(name, 0);

  // ---- start -------------------------------------------------------------------------------
  document.getElementById('title').textContent = data.robot + (data.target ? ' as compiled for ' + data.target : '');
  const counts = document.getElementById('counts');
  counts.textContent = data.links.length + ' links, ' + data.joints.length + ' joints, ' + data.meshes.length +
    ' meshes — ' + data.source.split(/[\\/]/).pop();
  counts.title = data.source + ' — ' + data.generator;
  document.getElementById('home').addEventListener('click', () => {
    for (const k of Object.keys(q)) delete q[k];
    for (const name in sliders) sliders[name].input.value = String(jointObjs[name].data.home);
    applyPose();
  });
  document.getElementById('fit').addEventListener('click', frame);

  Promise.all(data.meshes.map(parseGlb)).then((geometries) => {
    buildRobot(geometries);
    buildWorld(geometries);
    buildSliders();
    buildTree();
    buildFindings();
    buildRepairs();
    applyPose();
    const b = bounds();
    robotSize = b.getSize(new THREE.Vector3()).length();
    buildHelpers(robotSize);
    if (!data.world) { // a world draws its own ground
      const grid = new THREE.GridHelper(robotSize * 2, 20, 0xb0b4bc, 0xd4d7dd);
      grid.rotation.x = Math.PI / 2; // three's grid lies in XZ; the ground is XY here
      grid.position.set(0, 0, b.min.z);
      scene.add(grid);
    }
    bindToggles();
    resize();
    frame();
    renderNow();
    api.ready = true;
  });
})();
