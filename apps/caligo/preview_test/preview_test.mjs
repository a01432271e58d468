// The preview page in a real browser (Debian's Chromium through playwright-core): a render with
// --preview, the page loaded with the printed URL, the image updated between passes, a layer
// switched, the stop button pressed; the render then ends as after Ctrl-C (exit 130, partial
// image written). Also: a request without the token is refused.
//   node preview_test.mjs CALIGO WORKDIR [SCREENSHOT.png]
import { spawn } from "node:child_process";
import { existsSync } from "node:fs";
import { chromium } from "playwright-core";

const [caligo, work, screenshot] = process.argv.slice(2);
const fail = (message) => { console.error(`preview test: FAILED: ${message}`); process.exit(1); };
const render = spawn(caligo, ["render", "default", "--res", "240x180", "--spp", "4096", "--preview",
                              "-o", `${work}/p.exr`], { stdio: ["ignore", "ignore", "pipe"] });
let stderr = "";
const exited = new Promise((resolve) => render.on("exit", (code) => resolve(code)));
const url = await new Promise((resolve, reject) => {
  render.stderr.on("data", (chunk) => {
    stderr += chunk;
    const m = stderr.match(/preview at (http:\/\/127\.0\.0\.1:\d+\/\?token=[0-9a-f]+)/);
    if (m) resolve(m[1]);
  });
  setTimeout(() => reject(new Error("no preview URL within 20 s:\n" + stderr)), 20000);
}).catch((e) => fail(e.message));

const origin = new URL(url).origin;
const refused = await fetch(`${origin}/status`);
if (refused.status !== 403) fail(`a request without the token got ${refused.status}, not 403`);
const wrong = await fetch(`${origin}/image.png?token=0000`);
if (wrong.status !== 403) fail(`a request with a wrong token got ${wrong.status}, not 403`);

const browser = await chromium.launch({ executablePath: "/usr/bin/chromium", args: ["--no-sandbox"] });
try {
  const page = await browser.newPage({ viewport: { width: 900, height: 360 } });
  await page.goto(url);
  const shown = () => page.$eval("#image", (img) => Number(img.dataset.version));
  await page.waitForFunction(() => Number(document.getElementById("image").dataset.version) >= 0, null, { timeout: 20000 });
  const first = await shown();
  await page.waitForFunction((v) => Number(document.getElementById("image").dataset.version) > v, first, { timeout: 30000 });
  const second = await shown();
  console.log(`preview test: the image went from state ${first} to ${second} between passes`);
  await page.selectOption("#layer", "albedo");
  await page.waitForFunction(() => document.getElementById("image").dataset.layer === "albedo", null, { timeout: 10000 });
  const status = await page.textContent("#status");
  if (!/ \/ 4096 spp/.test(status)) fail(`the status line says "${status}"`);
  await page.selectOption("#layer", "beauty");
  await page.waitForFunction(() => document.getElementById("image").dataset.layer === "beauty", null, { timeout: 10000 });
  if (screenshot) await page.screenshot({ path: screenshot });
  await page.click("#stop");
  const code = await Promise.race([exited, new Promise((r) => setTimeout(() => r("timeout"), 30000))]);
  if (code !== 130) fail(`after stop the render exited with ${code}, not 130 (as after Ctrl-C):\n${stderr}`);
  if (!existsSync(`${work}/p.partial.exr`)) fail("no partial image after stop");
  console.log("preview test: stop ended the render as Ctrl-C does (exit 130, p.partial.exr written)");
} finally {
  await browser.close();
  render.kill("SIGKILL");
}
process.exit(0);  // the timers set above would keep Node.js waiting
