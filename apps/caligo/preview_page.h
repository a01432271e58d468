// The preview page (preview_server.h): one self-contained HTML file, no external resources.
// Elements carry ids the browser test drives (apps/caligo/preview_test/): #image (its
// data-version is the state shown), #layer, #exposure, #denoised, #stop, #status, #table.
#pragma once

namespace caligo {

inline constexpr const char* kPreviewPage = R"html(<!doctype html>
<html lang="en"><head><meta charset="utf-8"><title>Caligo preview</title>
<style>
body { margin: 0; background: #1e1e1e; color: #ddd; font: 13px system-ui, sans-serif; }
#bar { display: flex; gap: 14px; align-items: center; padding: 8px 12px; background: #2b2b2b; flex-wrap: wrap; }
#status { font-variant-numeric: tabular-nums; min-width: 22em; }
#view { padding: 12px; }
#image { image-rendering: pixelated; max-width: 100%; border: 1px solid #444; }
#table { white-space: pre; font: 12px ui-monospace, monospace; color: #bbb; padding: 0 12px; }
button { background: #a33; color: white; border: 0; padding: 5px 14px; border-radius: 3px; cursor: pointer; }
button:disabled { background: #555; cursor: default; }
</style></head>
<body>
<div id="bar">
  <span id="status">connecting</span>
  <label>exposure <input id="exposure" type="range" min="-8" max="8" step="0.25" value="0"> <span id="ev">0</span> EV</label>
  <label>layer <select id="layer"><option>beauty</option></select></label>
  <label><input id="denoised" type="checkbox" disabled> denoised</label>
  <button id="stop">stop</button>
</div>
<div id="view"><img id="image" alt="the render" data-version="-1"></div>
<div id="table"></div>
<script>
const token = new URLSearchParams(location.search).get("token") || "";
const $ = (id) => document.getElementById(id);
let version = -1, layers = "", finished = false;
function imageUrl() {
  const layer = $("denoised").checked ? "denoised" : $("layer").value;
  return `/image.png?token=${encodeURIComponent(token)}&layer=${encodeURIComponent(layer)}` +
         `&exposure=${$("exposure").value}&v=${version}`;
}
function refresh() {
  const shown = version;
  const img = new Image();
  img.onload = () => { $("image").src = img.src; $("image").dataset.version = String(shown);
                       $("image").dataset.layer = $("denoised").checked ? "denoised" : $("layer").value; };
  img.src = imageUrl();
}
async function poll() {
  try {
    const s = await (await fetch(`/status?token=${encodeURIComponent(token)}`)).json();
    const eta = s.finished ? "done" : (s.eta >= 0 ? `ETA ${s.eta.toFixed(1)} s` : "ETA -");
    $("status").textContent = `${s.done} / ${s.target} ${s.unit} · ${s.seconds.toFixed(1)} s · ${eta}` +
                              (s.stopping ? " · stopping" : "");
    $("table").textContent = s.table;
    if (s.layers.join(",") !== layers) {
      layers = s.layers.join(",");
      const current = $("layer").value;
      $("layer").innerHTML = "";
      for (const l of s.layers.filter((l) => l !== "denoised")) {
        const o = document.createElement("option"); o.textContent = l; $("layer").appendChild(o);
      }
      if (s.layers.includes(current)) $("layer").value = current;
      $("denoised").disabled = !s.layers.includes("denoised");
    }
    if (s.version !== version) { version = s.version; refresh(); }
    finished = s.finished;
    if (finished) $("stop").disabled = true;
  } catch (e) {
    $("status").textContent += " · the render has ended";
    $("stop").disabled = true;
    return;
  }
  setTimeout(poll, finished ? 2000 : 250);
}
$("exposure").addEventListener("input", () => { $("ev").textContent = $("exposure").value; refresh(); });
$("layer").addEventListener("change", refresh);
$("denoised").addEventListener("change", refresh);
$("stop").addEventListener("click", async () => {
  $("stop").disabled = true;
  await fetch(`/stop?token=${encodeURIComponent(token)}`, { method: "POST" });
});
poll();
</script>
</body></html>
)html";

}  // namespace caligo
