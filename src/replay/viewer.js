// steplearn replay viewer: draws the recording in #replay-data with THREE (defined above).
const errors = document.getElementById('errors');
const report = (msg) => { errors.textContent += msg + '\n'; document.body.dataset.errors = '1'; };
window.addEventListener('error', (e) => report('error: ' + e.message));
window.addEventListener('unhandledrejection', (e) => report('rejection: ' + e.reason));
try {
  main();
} catch (e) {
  report('error: ' + (e && e.stack ? e.stack : e));
}

function main() {
  const R = JSON.parse(document.getElementById('replay-data').textContent);
  const walks = R.walks.filter((w) => w.frames.length > 0);
  if (walks.length === 0) throw new Error('no frames recorded');
  const t0 = Math.min(...walks.map((w) => w.frames[0].t));
  const t1 = Math.max(...walks.map((w) => w.frames[w.frames.length - 1].t));
  const colors = [0x1f77b4, 0x7f7f7f, 0x2ca02c, 0x9467bd];
  const css = (c) => '#' + c.toString(16).padStart(6, '0');

  // --- scene -------------------------------------------------------------------------
  const canvas = document.getElementById('view');
  const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(1);
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0xdde4ea);
  const camera = new THREE.PerspectiveCamera(40, 1, 0.05, 100);
  camera.up.set(0, 0, 1);
  scene.add(new THREE.HemisphereLight(0xffffff, 0x667788, 1.6));
  const sun = new THREE.DirectionalLight(0xffffff, 1.4);
  sun.position.set(2, -3, 5);
  scene.add(sun);
  const ground = new THREE.Mesh(new THREE.PlaneGeometry(20, 20), new THREE.MeshLambertMaterial({ color: 0xc9c3b6 }));
  scene.add(ground);
  const grid = new THREE.GridHelper(20, 80, 0x999999, 0xb5b0a5);
  grid.rotation.x = Math.PI / 2;
  grid.position.z = 0.001;
  scene.add(grid);

  const bones = [[0, 1], [1, 2], [0, 3], [3, 4], [4, 5], [5, 6], [6, 7], [5, 7],
    [0, 8], [8, 9], [9, 10], [10, 11], [11, 12], [10, 12]];
  const up = new THREE.Vector3(0, 1, 0);
  const spacing = 1.0;
  let overlaid = false;

  const actors = walks.map((w, i) => {
    const group = new THREE.Group();
    scene.add(group);
    const mat = new THREE.MeshLambertMaterial({ color: colors[i % colors.length] });
    const sticks = bones.map(() => {
      const m = new THREE.Mesh(new THREE.CylinderGeometry(0.018, 0.018, 1, 10), mat);
      group.add(m);
      return m;
    });
    const head = new THREE.Mesh(new THREE.SphereGeometry(0.07, 16, 12), mat);
    group.add(head);
    // the robot's own links: its collision shapes, or boxes of its links' inertias
    const bodies = (w.bodies || []).map((shapes) => {
      const link = new THREE.Group();
      for (const sh of shapes) {
        let geo;
        if (sh.kind === 'box') geo = new THREE.BoxGeometry(sh.size[0], sh.size[1], sh.size[2]);
        else if (sh.kind === 'sphere') geo = new THREE.SphereGeometry(sh.size[0], 16, 12);
        else if (sh.kind === 'capsule') geo = new THREE.CapsuleGeometry(sh.size[0], sh.size[1], 4, 12);
        else geo = new THREE.CylinderGeometry(sh.size[0], sh.size[0], sh.size[1], 16);
        const mesh = new THREE.Mesh(geo, mat);
        if (sh.kind === 'capsule' || sh.kind === 'cylinder') mesh.rotation.x = Math.PI / 2;
        const holder = new THREE.Group();
        holder.position.set(sh.pos[0], sh.pos[1], sh.pos[2]);
        holder.quaternion.set(sh.quat[1], sh.quat[2], sh.quat[3], sh.quat[0]);
        holder.add(mesh);
        link.add(holder);
      }
      group.add(link);
      return link;
    });
    const drawn = bodies.length > 0 && w.frames.length > 0 && (w.frames[0].links || []).length === bodies.length;
    if (drawn) { for (const s of sticks) s.visible = false; head.visible = false; }
    const com = new THREE.Mesh(new THREE.SphereGeometry(0.03, 12, 8), new THREE.MeshLambertMaterial({ color: 0xd62728 }));
    group.add(com);
    const cp = new THREE.Mesh(new THREE.CylinderGeometry(0.03, 0.03, 0.004, 16), new THREE.MeshLambertMaterial({ color: 0xff7f0e }));
    cp.rotation.x = Math.PI / 2;
    group.add(cp);
    const cmd = new THREE.Mesh(new THREE.TorusGeometry(0.05, 0.008, 6, 24), new THREE.MeshLambertMaterial({ color: 0x1f3fd0 }));
    group.add(cmd);
    // footsteps of the recorded span: commanded (rings) and realised (boxes), shown once landed
    const steps = w.steps.map((s) => {
      const landed = new THREE.Mesh(new THREE.BoxGeometry(0.16, 0.07, 0.006), new THREE.MeshLambertMaterial({ color: 0x2ca02c }));
      landed.position.set(s.landed[0], s.landed[1], 0.003);
      group.add(landed);
      let ring = null;
      if (s.cmd) {
        ring = new THREE.Mesh(new THREE.TorusGeometry(0.04, 0.006, 6, 20), new THREE.MeshLambertMaterial({ color: 0x1f3fd0 }));
        ring.position.set(s.cmd[0], s.cmd[1], 0.006);
        group.add(ring);
      }
      return { t: s.t, landed, ring };
    });
    const arrow = new THREE.ArrowHelper(new THREE.Vector3(...R.direction), new THREE.Vector3(), 0.5, 0xe377c2, 0.12, 0.07);
    group.add(arrow);
    const fall = new THREE.Group();
    const xmat = new THREE.MeshLambertMaterial({ color: 0xd62728 });
    for (const a of [Math.PI / 4, -Math.PI / 4]) {
      const bar = new THREE.Mesh(new THREE.BoxGeometry(0.4, 0.05, 0.02), xmat);
      bar.rotation.z = a;
      fall.add(bar);
    }
    group.add(fall);
    return { w, group, sticks, head, bodies, drawn, com, cp, cmd, steps, arrow, fall, color: colors[i % colors.length] };
  });

  // --- orbit -------------------------------------------------------------------------
  const target = new THREE.Vector3();
  {
    const f = walks[0].frames[0].com;
    target.set(f[0], f[1] + (walks.length - 1) * spacing / 2, f[2] * 0.8);
  }
  const orbit = { r: 4.5, az: -0.7, el: 0.3 };
  const placeCamera = () => {
    camera.position.set(
      target.x + orbit.r * Math.cos(orbit.el) * Math.cos(orbit.az),
      target.y + orbit.r * Math.cos(orbit.el) * Math.sin(orbit.az),
      target.z + orbit.r * Math.sin(orbit.el));
    camera.lookAt(target);
  };
  let drag = null;
  canvas.addEventListener('pointerdown', (e) => { drag = [e.clientX, e.clientY]; canvas.setPointerCapture(e.pointerId); });
  canvas.addEventListener('pointerup', () => { drag = null; });
  canvas.addEventListener('pointermove', (e) => {
    if (!drag) return;
    orbit.az -= (e.clientX - drag[0]) * 0.008;
    orbit.el = Math.min(1.5, Math.max(0.02, orbit.el + (e.clientY - drag[1]) * 0.008));
    drag = [e.clientX, e.clientY];
    draw();
  });
  canvas.addEventListener('wheel', (e) => {
    e.preventDefault();
    orbit.r = Math.min(20, Math.max(0.5, orbit.r * Math.exp(e.deltaY * 0.001)));
    draw();
  }, { passive: false });

  // --- timeline ----------------------------------------------------------------------
  const tl = document.getElementById('timeline');
  const ctx = tl.getContext('2d');
  // A frame leaves out the sole's offsets when they are 0.
  const val = (f, key) => f[key] || 0;
  const has = (key) => walks.some((w) => w.frames.some((f) => val(f, key) !== 0));
  const series = [['d_f', 'dF (m)', []], ['d_w', 'dW (m)', [6, 3]], ['d_t', 'dT (s)', [2, 3]], ['d_a', 'sole pitch dA (rad)', [1, 2]], ['d_r', 'sole roll dR (rad)', [4, 2, 1, 2]], ['lean', 'trunk lean θE (rad)', [10, 3, 2, 3]]]
    .filter(([k]) => k === 'lean' || k === 'd_f' || has(k));
  document.getElementById('legend').innerHTML =
    actors.map((a) => `<span class="key" style="background:${css(a.color)}"></span>${a.w.name}` +
      (R.span ? (a.w.fall_time != null ? ' (fell at ' + a.w.fall_time.toFixed(2) + ' s)' : '')
        : a.w.fell ? ' (fell' + (a.w.fall_time != null ? ' at ' + a.w.fall_time.toFixed(2) + ' s' : '') + ')' : ' (absorbed)')).join('') +
    ((R.changes || []).length ? ' &middot; reference F_R: ' + R.changes.map(([ct, v]) => `${v.toFixed(3)} m from ${ct.toFixed(2)} s`).join(', ') + ' (grey lines: changes)' : '') +
    ' &middot; lines: ' + series.map(([, label, dash]) => `${label} ${dash.length ? '(dashed ' + dash.join('-') + ')' : '(solid)'}`).join(', ');
  const drawTimeline = (t) => {
    const W = tl.clientWidth || 800, H = tl.clientHeight || 180;
    if (tl.width !== W) tl.width = W;
    if (tl.height !== H) tl.height = H;
    ctx.clearRect(0, 0, W, H);
    let lo = 0, hi = 0;
    for (const w of walks) for (const f of w.frames) for (const [k] of series) { lo = Math.min(lo, val(f, k)); hi = Math.max(hi, val(f, k)); }
    if (hi - lo < 1e-6) { hi += 0.05; lo -= 0.05; }
    const x = (s) => 40 + (W - 50) * (s - t0) / Math.max(1e-9, t1 - t0);
    const y = (v) => H - 15 - (H - 25) * (v - lo) / (hi - lo);
    ctx.strokeStyle = '#ccc'; ctx.lineWidth = 1; ctx.setLineDash([]);
    ctx.beginPath(); ctx.moveTo(40, y(0)); ctx.lineTo(W - 10, y(0)); ctx.stroke();
    ctx.fillStyle = '#444'; ctx.font = '11px sans-serif';
    ctx.fillText(hi.toFixed(3), 2, 12); ctx.fillText(lo.toFixed(3), 2, H - 15);
    ctx.fillText(t0.toFixed(2) + ' s', 40, H - 2); ctx.fillText(t1.toFixed(2) + ' s', W - 60, H - 2);
    ctx.strokeStyle = '#999';
    for (const [ct] of (R.changes || []).slice(1)) { ctx.beginPath(); ctx.moveTo(x(ct), 5); ctx.lineTo(x(ct), H - 15); ctx.stroke(); }
    for (const a of actors) {
      if (a.w.push_time != null) { ctx.strokeStyle = '#e377c2'; ctx.beginPath(); ctx.moveTo(x(a.w.push_time), 5); ctx.lineTo(x(a.w.push_time), H - 15); ctx.stroke(); }
      for (const [k, , dash] of series) {
        ctx.strokeStyle = css(a.color); ctx.lineWidth = 1.5; ctx.setLineDash(dash);
        ctx.beginPath();
        a.w.frames.forEach((f, i) => (i ? ctx.lineTo(x(f.t), y(val(f, k))) : ctx.moveTo(x(f.t), y(val(f, k)))));
        ctx.stroke();
      }
    }
    ctx.setLineDash([]); ctx.strokeStyle = '#000'; ctx.lineWidth = 1;
    ctx.beginPath(); ctx.moveTo(x(t), 0); ctx.lineTo(x(t), H); ctx.stroke();
  };
  tl.addEventListener('pointerdown', (e) => {
    const r = tl.getBoundingClientRect();
    time = t0 + (t1 - t0) * Math.min(1, Math.max(0, (e.clientX - r.left - 40) / (r.width - 50)));
    draw();
  });

  // --- state at a time ---------------------------------------------------------------
  const frameAt = (w, t) => {
    let lo = 0, hi = w.frames.length - 1;
    if (t <= w.frames[0].t) return w.frames[0];
    if (t >= w.frames[hi].t) return w.frames[hi];
    while (hi - lo > 1) { const m = (lo + hi) >> 1; if (w.frames[m].t <= t) lo = m; else hi = m; }
    return w.frames[lo];
  };
  const a3 = new THREE.Vector3(), b3 = new THREE.Vector3(), d3 = new THREE.Vector3();
  const pose = (a, t) => {
    const f = frameAt(a.w, t);
    const i = actors.indexOf(a);
    a.group.position.set(0, overlaid ? 0 : i * spacing, 0);
    bones.forEach(([p, q], k) => {
      a3.set(...f.pts[p]); b3.set(...f.pts[q]);
      const s = a.sticks[k];
      d3.subVectors(b3, a3);
      const len = Math.max(1e-4, d3.length());
      s.position.addVectors(a3, b3).multiplyScalar(0.5);
      s.scale.set(1, len, 1);
      s.quaternion.setFromUnitVectors(up, d3.divideScalar(len));
    });
    a.head.position.set(...f.pts[2]);
    if (a.drawn) {
      a.bodies.forEach((link, k) => {
        const l = f.links[k];
        link.position.set(l[0], l[1], l[2]);
        link.quaternion.set(l[4], l[5], l[6], l[3]);
      });
    }
    a.com.position.set(...f.com);
    a.cp.position.set(f.cp[0], f.cp[1], 0.004);
    a.cmd.visible = !!f.cmd;
    if (f.cmd) a.cmd.position.set(f.cmd[0], f.cmd[1], 0.008);
    for (const s of a.steps) { s.landed.visible = t >= s.t; if (s.ring) s.ring.visible = t >= s.t; }
    const pt = a.w.push_time;
    a.arrow.visible = pt != null && t >= pt - 0.3 && t <= pt + 0.5;
    if (a.arrow.visible) {
      const d = R.direction;
      a.arrow.position.set(f.com[0] - 0.6 * d[0], f.com[1] - 0.6 * d[1], f.com[2] - 0.6 * d[2]);
    }
    a.fall.visible = a.w.fall_time != null && t >= a.w.fall_time;
    if (a.fall.visible) {
      const last = a.w.frames[a.w.frames.length - 1];
      a.fall.position.set(last.com[0], last.com[1], 0.02);
    }
  };

  // --- playback ----------------------------------------------------------------------
  let time = t0, playing = true, last = performance.now(), drawn = 0;
  const scrub = document.getElementById('scrub');
  const clock = document.getElementById('clock');
  const speed = document.getElementById('speed');
  const play = document.getElementById('play');
  play.onclick = () => { playing = !playing; play.textContent = playing ? 'pause' : 'play'; };
  scrub.oninput = () => { time = t0 + (t1 - t0) * scrub.value / 1000; draw(); };
  document.getElementById('overlay').onchange = (e) => { overlaid = e.target.checked; draw(); };
  const resize = () => {
    const w = canvas.clientWidth || 800, h = canvas.clientHeight || 450;
    renderer.setSize(w, h, false);
    camera.aspect = w / h;
    camera.updateProjectionMatrix();
  };
  function draw() {
    resize();
    for (const a of actors) pose(a, time);
    placeCamera();
    renderer.render(scene, camera);
    drawTimeline(time);
    scrub.value = Math.round(1000 * (time - t0) / Math.max(1e-9, t1 - t0));
    clock.textContent = time.toFixed(2) + ' s';
    drawn += 1;
    const b = document.body.dataset;
    b.framesDrawn = String(drawn);
    if (drawn === 1) { b.firstTime = time.toFixed(4); b.nonblank = String(nonblank()); }
    // the largest distance of a drawn moment from the first (playback that loops back to the
    // start still moved)
    b.moved = Math.max(Number(b.moved || 0), Math.abs(time - Number(b.firstTime))).toFixed(4);
  }
  // pixels of the first picture that differ from the background: the walkers were drawn
  function nonblank() {
    const gl = renderer.getContext();
    const w = gl.drawingBufferWidth, h = gl.drawingBufferHeight;
    const px = new Uint8Array(w * h * 4);
    gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, px);
    let n = 0;
    for (let i = 0; i < px.length; i += 4) {
      const r = px[i], g = px[i + 1], bl = px[i + 2];
      // neither the sky nor the ground nor the grid: a coloured body or marker
      const grey = Math.max(r, g, bl) - Math.min(r, g, bl) < 40;
      if (!grey) n += 1;
    }
    return n;
  }
  const tick = () => {
    const now = performance.now();
    if (playing) {
      time += (now - last) / 1000 * Number(speed.value);
      if (time > t1) time = t0;
    }
    last = now;
    draw();
  };
  draw();
  setInterval(tick, 40);
  window.addEventListener('resize', draw);
}
