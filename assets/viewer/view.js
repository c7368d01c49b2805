// The report page's 3D view: the scene of view-data.js in the page's <model-viewer>, with
// play, pause, a time slider with the worst moment marked, a button that turns the camera to
// the worst spot and rings it, and clamp labels that follow their links. Written by cable-dict into every report folder; needs nothing outside it.
//
// A page opened from file:// may not fetch its neighbours, so the scene comes as base64 in
// view-data.js (a plain script) and is handed to model-viewer as a blob: URL. Names from the
// inputs are only ever set as text (textContent), never as markup.
(function () {
  "use strict";
  const data = window.cableDictView;
  const viewer = document.getElementById("view");
  if (!data || !viewer) return;

  const bytes = Uint8Array.from(atob(data.glb_base64), (c) => c.charCodeAt(0));
  viewer.src = URL.createObjectURL(new Blob([bytes], { type: "model/gltf-binary" }));

  const install = document.getElementById("view-install");
  const play = document.getElementById("view-play");
  const slider = document.getElementById("view-time");
  const readout = document.getElementById("view-readout");
  const worstButton = document.getElementById("view-worst");
  const worstTick = document.getElementById("view-worst-tick");
  const picker = document.getElementById("view-motion");
  // The motion test played: the one the report shows, or a cell's other motion picked.
  let clip = data.clips[0];
  let duration = 0;

  data.clamps.forEach((clamp, i) => {
    const label = document.createElement("div");
    label.slot = `hotspot-clamp-${i}`;
    label.className = "clamp-label";
    label.dataset.position = position(clip.positions_m[i][0]);
    label.textContent = clamp.label;
    viewer.appendChild(label);
  });

  function position(p) {
    return `${p[0]}m ${p[1]}m ${p[2]}m`;
  }

  // The red ring at the worst spot, shown at the worst moment only.
  const ring = document.createElement("div");
  ring.slot = "hotspot-worst";
  ring.className = "worst-ring";
  ring.hidden = true;
  ring.dataset.position = "0m 0m 0m";
  viewer.appendChild(ring);
  const RING_WITHIN_S = 0.05;

  // Index of the last keyframe at or before t, and the share of the way to the next one.
  function keyframe(t) {
    const times = clip.times_s;
    let lo = 0;
    let hi = times.length - 1;
    if (hi <= 0 || t <= times[0]) return [0, 0];
    if (t >= times[hi]) return [hi, 0];
    while (hi - lo > 1) {
      const mid = (lo + hi) >> 1;
      if (times[mid] <= t) lo = mid;
      else hi = mid;
    }
    return [lo, (t - times[lo]) / (times[lo + 1] - times[lo])];
  }

  function moveLabels(t) {
    const [k, s] = keyframe(t);
    clip.positions_m.forEach((track, i) => {
      const a = track[k];
      const b = track[Math.min(k + 1, track.length - 1)];
      const p = a.map((x, j) => x + s * (b[j] - x));
      viewer.updateHotspot({ name: `hotspot-clamp-${i}`, position: position(p) });
    });
  }

  function show(t) {
    slider.value = String(t);
    const end = clip.motion_end_s;
    const held = end !== null && end !== undefined && t > end + 1e-6;
    const motionEnd = end !== null && end !== undefined ? `; the motion ends at ${end.toFixed(2)} s` : "";
    readout.textContent = held
      ? `t = ${t.toFixed(2)} s: the motion's last pose held, the cable coming to rest${motionEnd}`
      : `t = ${t.toFixed(2)} s of ${duration.toFixed(2)} s${motionEnd}`;
    ring.hidden = !(clip.worst && clip.worst.spot_m && Math.abs(t - clip.worst.time_s) <= RING_WITHIN_S);
    moveLabels(t);
  }

  function tick() {
    show(viewer.currentTime);
    if (!viewer.paused) requestAnimationFrame(tick);
  }

  // Makes `name` the current animation. model-viewer applies a newly chosen clip only while
  // it plays (with no cross-fade: the element says so), so it plays for two frames first.
  function useAnimation(name) {
    if (viewer.animationName === name) return Promise.resolve();
    viewer.animationName = name;
    viewer.play();
    return new Promise((resolve) =>
      requestAnimationFrame(() =>
        requestAnimationFrame(() => {
          viewer.pause();
          resolve();
        }),
      ),
    );
  }

  // The motion test at time t, paused.
  async function seek(t) {
    viewer.pause();
    if (clip.animation) await useAnimation(clip.animation);
    viewer.currentTime = t;
    play.textContent = "Play";
    install.classList.remove("active");
    show(t);
  }

  // The robot at the installation pose with the cable laid there (a still animation), the
  // labels at their places in it.
  async function showInstallation() {
    viewer.pause();
    await useAnimation(data.installation);
    viewer.currentTime = 0;
    play.textContent = "Play";
    install.classList.add("active");
    readout.textContent = "installation pose";
    ring.hidden = true;
    data.clamps.forEach((clamp, i) => {
      viewer.updateHotspot({ name: `hotspot-clamp-${i}`, position: position(clamp.installation_m) });
    });
  }

  // The controls for the clip played: its length, its worst moment.
  function useClip(k) {
    clip = data.clips[k];
    duration = clip.times_s.length ? clip.times_s[clip.times_s.length - 1] : 0;
    slider.max = String(duration);
    slider.step = "0.01";
    const worst = clip.worst;
    worstTick.hidden = !worst;
    worstButton.hidden = !worst;
    if (worst) {
      worstTick.style.left = `${(100 * worst.time_s) / Math.max(duration, 1e-9)}%`;
      worstTick.title = worst.what;
      worstButton.textContent = `Worst moment: ${worst.what}`;
      if (worst.spot_m) ring.dataset.position = position(worst.spot_m);
    }
    for (const control of [play, slider, worstButton]) control.disabled = !clip.animation;
  }
  useClip(0);
  install.hidden = !data.installation;
  // A cell's motions: one choice each, names set as text.
  picker.hidden = data.clips.length < 2;
  data.clips.forEach((c, k) => {
    const option = document.createElement("option");
    option.value = String(k);
    option.textContent = c.label;
    picker.appendChild(option);
  });
  picker.addEventListener("change", async () => {
    useClip(Number(picker.value));
    if (clip.worst && clip.worst.spot_m) viewer.updateHotspot({ name: "hotspot-worst", position: ring.dataset.position });
    await seek(0);
  });

  // A scene with the cable's damage per cycle offers it as a second colouring (a glTF
  // material variant); the first, by margins, is the default.
  const colour = document.getElementById("view-colour");
  const damageLegend = document.getElementById("view-damage-legend");
  colour.addEventListener("change", () => {
    viewer.variantName = colour.value;
    damageLegend.hidden = colour.selectedIndex === 0;
  });

  viewer.addEventListener("load", async () => {
    const variants = viewer.availableVariants || [];
    colour.hidden = !Array.from(colour.options).every((o) => variants.includes(o.value));
    if (clip.animation) await seek(0);
    document.body.dataset.viewLoaded = "true";
  });
  install.addEventListener("click", showInstallation);
  play.addEventListener("click", async () => {
    if (viewer.animationName !== clip.animation) await seek(Number(slider.value));
    if (viewer.paused) {
      if (viewer.currentTime >= duration) viewer.currentTime = 0;
      viewer.play();
      play.textContent = "Pause";
      requestAnimationFrame(tick);
    } else {
      seek(viewer.currentTime);
    }
  });
  slider.addEventListener("input", () => seek(Number(slider.value)));
  // The worst moment: the time there, the camera turned to the spot from outside the arm.
  worstButton.addEventListener("click", async () => {
    const worst = clip.worst;
    if (!worst) return;
    await seek(worst.time_s);
    if (worst.spot_m && worst.orbit) {
      const [azimuth, polar, distance] = worst.orbit;
      viewer.cameraTarget = position(worst.spot_m);
      viewer.cameraOrbit = `${azimuth}deg ${polar}deg ${distance}m`;
    }
  });
})();
