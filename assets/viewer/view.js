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
  const duration = data.times_s.length ? data.times_s[data.times_s.length - 1] : 0;

  data.clamps.forEach((clamp, i) => {
    const label = document.createElement("div");
    label.slot = `hotspot-clamp-${i}`;
    label.className = "clamp-label";
    label.dataset.position = position(clamp.positions_m[0]);
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
  if (data.worst && data.worst.spot_m) {
    ring.dataset.position = position(data.worst.spot_m);
    viewer.appendChild(ring);
  }
  const RING_WITHIN_S = 0.05;

  // Index of the last keyframe at or before t, and the share of the way to the next one.
  function keyframe(t) {
    const times = data.times_s;
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
    data.clamps.forEach((clamp, i) => {
      const a = clamp.positions_m[k];
      const b = clamp.positions_m[Math.min(k + 1, clamp.positions_m.length - 1)];
      const p = a.map((x, j) => x + s * (b[j] - x));
      viewer.updateHotspot({ name: `hotspot-clamp-${i}`, position: position(p) });
    });
  }

  function show(t) {
    slider.value = String(t);
    const end = data.motion_end_s;
    const held = end !== null && end !== undefined && t > end + 1e-6;
    const motionEnd = end !== null && end !== undefined ? `; the motion ends at ${end.toFixed(2)} s` : "";
    readout.textContent = held
      ? `t = ${t.toFixed(2)} s: the motion's last pose held, the cable coming to rest${motionEnd}`
      : `t = ${t.toFixed(2)} s of ${duration.toFixed(2)} s${motionEnd}`;
    ring.hidden = !(data.worst && Math.abs(t - data.worst.time_s) <= RING_WITHIN_S);
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
    if (data.animation) await useAnimation(data.animation);
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

  slider.max = String(duration);
  slider.step = "0.01";
  if (data.worst) {
    worstTick.style.left = `${(100 * data.worst.time_s) / Math.max(duration, 1e-9)}%`;
    worstTick.title = data.worst.what;
    worstButton.textContent = `Worst moment: ${data.worst.what}`;
  } else {
    worstButton.hidden = true;
  }
  if (!data.animation) {
    for (const control of [play, slider, worstButton]) control.disabled = true;
  }
  install.hidden = !data.installation;

  viewer.addEventListener("load", async () => {
    if (data.animation) await seek(0);
    document.body.dataset.viewLoaded = "true";
  });
  install.addEventListener("click", showInstallation);
  play.addEventListener("click", async () => {
    if (viewer.animationName !== data.animation) await seek(Number(slider.value));
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
    if (!data.worst) return;
    await seek(data.worst.time_s);
    if (data.worst.spot_m && data.worst.orbit) {
      const [azimuth, polar, distance] = data.worst.orbit;
      viewer.cameraTarget = position(data.worst.spot_m);
      viewer.cameraOrbit = `${azimuth}deg ${polar}deg ${distance}m`;
    }
  });
})();
