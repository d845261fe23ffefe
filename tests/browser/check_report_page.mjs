// One browser check of a report page, in Debian's headless Chromium driven by playwright-core.
//
//   node check_report_page.mjs --page FILE
//        --check console|network|canvas|garment-pixels|ease-pixels|garment-toggle|frame-slider|
//                frame-pixels
//                              [--screenshot OUT.png]
//
// Exits 0 when the check passes, 1 with the reason when it fails. The page is opened from
// file:// as a user opens it; WebGL runs on SwiftShader (no GPU here).
import { chromium } from 'playwright-core';
import { resolve } from 'node:path';
import { pathToFileURL } from 'node:url';
import { writeFileSync } from 'node:fs';

const VIEWPORT = { width: 1280, height: 860 };
// A pixel this far (per channel) from the background colour counts as drawn.
const DRAWN = 12;
// Hue tolerance (degrees) between a rendered garment pixel and the colour its vertex got:
// lighting scales a colour, it does not turn it.
const HUE_DEGREES = 25;

function parseArguments(argv) {
  const options = {};
  for (let i = 0; i < argv.length; i += 2) options[argv[i].replace(/^--/, '')] = argv[i + 1];
  if (!options.page || !options.check) {
    console.error('usage: node check_report_page.mjs --page FILE --check NAME [--screenshot OUT.png]');
    process.exit(2);
  }
  return options;
}

class CheckFailed extends Error {}
function expect(condition, message) {
  if (!condition) throw new CheckFailed(message);
}

async function launch() {
  return chromium.launch({
    executablePath: process.env.GR_CHROMIUM || '/usr/bin/chromium',
    args: ['--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
  });
}

// Opens the page and waits until the view has drawn; `watch` sees the page before it loads.
async function openReport(browser, url, watch = () => {}) {
  const context = await browser.newContext({ viewport: VIEWPORT, deviceScaleFactor: 1 });
  const page = await context.newPage();
  const errors = [];
  page.on('console', (m) => { if (m.type() === 'error') errors.push(`console: ${m.text()}`); });
  page.on('pageerror', (e) => errors.push(`uncaught: ${e.message}`));
  await watch(page, context);
  await page.goto(url, { waitUntil: 'load' });
  try {
    await page.waitForFunction(() => window.grView !== undefined, null, { timeout: 30000 });
  } catch {
    throw new CheckFailed(`the 3D view did not start; errors: ${errors.join(' | ') || 'none'}`);
  }
  return { page, errors };
}

// A user's session: every toggle and checkbox, an orbit drag and a zoom.
async function exercise(page) {
  for (const button of await page.locator('.shape-button').all()) await button.click();
  for (const box of await page.locator('.toolbar input[type=checkbox]').all()) {
    await box.click();
    await box.click();
  }
  await page.keyboard.press('t');
  const box = await page.locator('#gr-view canvas').boundingBox();
  await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
  await page.mouse.down();
  await page.mouse.move(box.x + box.width / 2 + 120, box.y + box.height / 2 + 30, { steps: 8 });
  await page.mouse.up();
  await page.mouse.wheel(0, -240);
  await page.locator('#gr-reset').click();
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
}

// Decodes PNG screenshots in a blank page of the same browser (window.images there) and
// runs `analyse` on them in that page, so no image library is needed and only small
// results travel back.
async function analysePngs(browser, pngs, analyse, argument) {
  const page = await browser.newPage();
  try {
    await page.evaluate(async (encoded) => {
      window.images = [];
      for (const base64 of encoded) {
        const bytes = Uint8Array.from(atob(base64), (c) => c.charCodeAt(0));
        const bitmap = await createImageBitmap(new Blob([bytes], { type: 'image/png' }),
                                               { colorSpaceConversion: 'none', premultiplyAlpha: 'none' });
        const canvas = new OffscreenCanvas(bitmap.width, bitmap.height);
        const context = canvas.getContext('2d');
        context.drawImage(bitmap, 0, 0);
        window.images.push(context.getImageData(0, 0, bitmap.width, bitmap.height));
      }
    }, pngs.map((png) => png.toString('base64')));
    return await page.evaluate(analyse, argument);
  } finally {
    await page.close();
  }
}

// Pixels of the first image further than `tolerance` from `background` (runs in the browser).
function countDrawn({ background, tolerance }) {
  const image = window.images[0];
  let drawn = 0;
  for (let i = 0; i < image.data.length; i += 4) {
    const d = Math.max(Math.abs(image.data[i] - background[0]), Math.abs(image.data[i + 1] - background[1]),
                       Math.abs(image.data[i + 2] - background[2]));
    if (d > tolerance) ++drawn;
  }
  return { drawn, total: image.width * image.height };
}

// Pixels at which the first two images differ (runs in the browser).
function countDifferent({ tolerance }) {
  const [a, b] = window.images;
  let different = 0;
  for (let i = 0; i < a.data.length; i += 4)
    for (let k = 0; k < 3; ++k)
      if (Math.abs(a.data[i + k] - b.data[i + k]) > tolerance) { ++different; break; }
  return different;
}

// The colours of the first image around each point (3×3 pixels; runs in the browser).
function coloursAround(points) {
  const image = window.images[0];
  return points.map(({ x, y }) => {
    const around = [];
    for (let dy = -1; dy <= 1; ++dy)
      for (let dx = -1; dx <= 1; ++dx) {
        const px = Math.round(x) + dx, py = Math.round(y) + dy;
        if (px < 0 || py < 0 || px >= image.width || py >= image.height) continue;
        const i = 4 * (py * image.width + px);
        around.push([image.data[i], image.data[i + 1], image.data[i + 2]]);
      }
    return around;
  });
}

function hueSaturation([r, g, b]) {
  const hi = Math.max(r, g, b), lo = Math.min(r, g, b), chroma = hi - lo;
  if (chroma === 0) return [0, 0];
  let hue;
  if (hi === r) hue = 60 * ((((g - b) / chroma) % 6) + 6) % 360;
  else if (hi === g) hue = 60 * ((b - r) / chroma + 2);
  else hue = 60 * ((r - g) / chroma + 4);
  return [hue, chroma / hi];
}

function sameHue(seen, expected) {
  const [h1, s1] = hueSaturation(seen);
  const [h2, s2] = hueSaturation(expected);
  const d = Math.abs(h1 - h2);
  return s1 > 0.2 && s2 > 0.2 && Math.min(d, 360 - d) <= HUE_DEGREES;
}

const checks = {
  // No console error or uncaught exception while loading and using the page.
  async console(browser, url) {
    const { page, errors } = await openReport(browser, url);
    await exercise(page);
    expect(errors.length === 0, `console errors: ${errors.join(' | ')}`);
    return 'no console errors while loading, toggling, orbiting and zooming';
  },

  // Every request the page makes is intercepted: only the page itself may be loaded.
  async network(browser, url) {
    const seen = [];
    const { page } = await openReport(browser, url, async (p, context) => {
      p.on('request', (r) => seen.push(r.url()));
      await context.route('**/*', (route) => {
        seen.push(route.request().url());
        return route.request().url() === url ? route.continue() : route.abort();
      });
    });
    await exercise(page);
    const resources = await page.evaluate(() => performance.getEntriesByType('resource').map((e) => e.name));
    const others = [...seen, ...resources].filter((u) => u !== url);
    expect(seen.includes(url), `the page's own request was not seen (${seen.join(', ')})`);
    expect(others.length === 0, `requests besides the page: ${others.join(', ')}`);
    return `one request (the page itself), ${resources.length} resource entries`;
  },

  // The canvas draws something in every shape of the toggle, and toggling changes it.
  async canvas(browser, url, options) {
    const { page, errors } = await openReport(browser, url);
    const background = await page.evaluate(
      () => JSON.parse(document.getElementById('gr-scene').textContent).colours.background);
    const count = await page.evaluate(() => window.grView.shapeCount);
    const shots = [];
    const summary = [];
    for (let shape = 0; shape < count; ++shape) {
      await page.evaluate((s) => window.grView.setShape(s), shape);
      const png = await page.locator('#gr-view canvas').screenshot();
      const { drawn, total } = await analysePngs(browser, [png], countDrawn, { background, tolerance: DRAWN });
      expect(drawn > 0.02 * total, `shape ${shape}: only ${drawn} of ${total} canvas pixels drawn`);
      shots.push(png);
      summary.push(`shape ${shape}: ${(100 * drawn / total).toFixed(1)}% drawn`);
      if (options.screenshot) writeFileSync(options.screenshot.replace(/\.png$/, `_shape${shape}.png`), png);
    }
    if (count > 1) {
      const different = await analysePngs(browser, shots.slice(0, 2), countDifferent, { tolerance: DRAWN });
      expect(different > 1000, `toggling the shape changed only ${different} pixels`);
      summary.push(`${different} pixels differ between shapes`);
    }
    expect(errors.length === 0, `console errors: ${errors.join(' | ')}`);
    return summary.join('; ');
  },

  // In a screenshot, garment vertices seen from the camera show the colour they were given.
  async 'garment-pixels'(browser, url, options) {
    return garmentPixels(browser, url, options, async () => {});
  },

  // An outfit page: each garment's box hides that garment alone and shows it again.
  async 'garment-toggle'(browser, url) {
    const { page, errors } = await openReport(browser, url);
    const background = await page.evaluate(
      () => JSON.parse(document.getElementById('gr-scene').textContent).colours.background);
    const count = await page.locator('.garment-toggle').count();
    const garments = await page.evaluate(
      () => JSON.parse(document.getElementById('gr-scene').textContent).garments.length);
    expect(count === garments && count >= 2, `${count} garment boxes for ${garments} garments`);
    const inSight = (g) => page.evaluate((garment) => {
      const n = window.grView.vertexCount(garment);
      const stride = Math.max(1, Math.floor(n / 600));
      let seen = 0;
      for (let v = 0; v < n; v += stride) if (window.grView.probe(garment, v).visible) ++seen;
      return seen;
    }, g);
    const canvas = page.locator('#gr-view canvas');
    const summary = [];
    for (let g = 0; g < count; ++g) {
      // This garment alone, so that no other one covers it.
      for (let other = 0; other < count; ++other)
        await page.locator(`#gr-garment-${other}`).setChecked(other === g);
      const alone = await inSight(g);
      expect(alone >= 10, `garment ${g}: only ${alone} vertices in sight with its box ticked`);
      const shown = await canvas.screenshot();
      await page.locator(`#gr-garment-${g}`).uncheck();
      const hidden = await inSight(g);
      expect(hidden === 0, `garment ${g}: ${hidden} vertices still in sight with its box unticked`);
      const gone = await canvas.screenshot();
      const { drawn } = await analysePngs(browser, [gone], countDrawn, { background, tolerance: DRAWN });
      expect(drawn > 0, 'the avatar is not drawn once the garments are hidden');
      const different = await analysePngs(browser, [shown, gone], countDifferent, { tolerance: DRAWN });
      expect(different > 1000, `garment ${g}: unticking its box changed only ${different} pixels`);
      await page.locator(`#gr-garment-${g}`).check();
      expect(await inSight(g) === alone, `garment ${g}: not shown again when its box is ticked`);
      summary.push(`garment ${g}: ${alone} vertices in sight, none unticked, ${different} pixels hidden`);
    }
    expect(errors.length === 0, `console errors: ${errors.join(' | ')}`);
    return summary.join('; ');
  },

  // A page with a clip: the slider poses the garment (its pixels and vertices move between
  // the first and the last frame), the ticks mark the crossing frames with the first and the
  // worst where the page data puts them, the worst frame's button shows it, and play
  // advances the frames until paused.
  async 'frame-slider'(browser, url, options) {
    const { page, errors } = await openReport(browser, url);
    const clip = await page.evaluate(() => {
      const a = JSON.parse(document.getElementById('gr-scene').textContent).animation;
      if (!a) return null;
      const pairs = a.times.map((_, f) => a.avatar_pairs[f] + a.self_pairs[f] + a.layer_pairs[f]);
      return { count: a.frame_count, worst: a.worst_frame, first: a.first_crossing, pairs };
    });
    expect(clip !== null, 'the page has no animation');
    expect(clip.count >= 2, `the clip has ${clip.count} frames`);
    expect(await page.evaluate(() => window.grView.frameCount) === clip.count,
           'grView.frameCount is not the page data\'s frame count');
    expect(await page.evaluate(() => window.grView.frame()) === -1, 'the page opens on a frame');

    // Ticks: one per crossing frame; the worst and the first where the page data says.
    const crossing = clip.pairs.filter((p) => p > 0).length;
    const ticks = await page.locator('.frame-marks .mark').count();
    expect(ticks === crossing, `${ticks} ticks for ${crossing} crossing frames`);
    const maxPairs = Math.max(...clip.pairs);
    if (maxPairs === 0) {
      // Every frame free (a certified retarget): nothing to mark, no worst frame to go to.
      expect(clip.worst === null && clip.first === null, 'a worst frame in a clip that never crosses');
      expect(await page.locator('#gr-worst').count() === 0, 'a worst-frame button with no crossing');
    } else {
      const worstTick = Number(await page.locator('#gr-mark-worst').getAttribute('data-frame'));
      expect(worstTick === clip.worst, `worst-frame tick at ${worstTick}, page data ${clip.worst}`);
      const firstTick = clip.first === clip.worst ? worstTick
        : Number(await page.locator('#gr-mark-first').getAttribute('data-frame'));
      expect(firstTick === clip.first, `first-crossing tick at ${firstTick}, page data ${clip.first}`);
      expect(clip.pairs[clip.worst] === maxPairs && clip.pairs.indexOf(maxPairs) === clip.worst,
             `frame ${clip.worst} is not the first with the most pairs (${maxPairs})`);
    }

    // The slider poses the garment: with the avatar hidden, the first and last frames differ.
    await page.locator('#gr-body').uncheck();
    const slider = page.locator('#gr-frame');
    const canvas = page.locator('#gr-view canvas');
    const shotAt = async (f) => {
      await slider.fill(String(f));
      expect(await page.evaluate(() => window.grView.frame()) === f, `the slider at ${f} shows another frame`);
      const info = await page.locator('#gr-frame-info').textContent();
      expect(info.startsWith(`frame ${f} of ${clip.count}`), `frame ${f}: the line reads "${info}"`);
      return canvas.screenshot();
    };
    const vertices = (f) => page.evaluate((frame) => {
      window.grView.setFrame(frame);
      const n = window.grView.vertexCount(0);
      const stride = Math.max(1, Math.floor(n / 200));
      const out = [];
      for (let v = 0; v < n; v += stride) out.push(window.grView.probe(0, v));
      return out;
    }, f);
    const last = clip.count - 1;
    const firstShot = await shotAt(0);
    const lastShot = await shotAt(last);
    if (options.screenshot) {
      writeFileSync(options.screenshot.replace(/\.png$/, '_first.png'), firstShot);
      writeFileSync(options.screenshot.replace(/\.png$/, '_last.png'), lastShot);
    }
    const different = await analysePngs(browser, [firstShot, lastShot], countDifferent, { tolerance: DRAWN });
    expect(different > 1000, `frames 0 and ${last} differ in only ${different} garment pixels`);
    const [from, to] = [await vertices(0), await vertices(last)];
    const moved = from.map((p, i) => Math.hypot(p.x - to[i].x, p.y - to[i].y));
    const largest = Math.max(...moved);
    expect(largest > 20, `garment vertices move at most ${largest.toFixed(1)} px between frames`);

    // The worst frame's button.
    if (clip.worst !== null) {
      await page.locator('#gr-worst').click();
      expect(await page.evaluate(() => window.grView.frame()) === clip.worst, 'the worst-frame button shows another frame');
    }

    // Play advances the frames, pause stops them.
    await slider.fill('0');
    await page.locator('#gr-play').click();
    await page.waitForTimeout(500);
    const playing = await page.evaluate(() => [window.grView.playing(), window.grView.frame()]);
    expect(playing[0] && playing[1] > 0, `after 0.5 s of play: playing ${playing[0]}, frame ${playing[1]}`);
    await page.locator('#gr-play').click();
    const paused = await page.evaluate(() => window.grView.frame());
    await page.waitForTimeout(300);
    expect(await page.evaluate(() => window.grView.frame()) === paused, 'the frames advance after pause');
    expect(errors.length === 0, `console errors: ${errors.join(' | ')}`);
    return `${clip.count} frames, ${ticks} crossing ticks, worst ${clip.worst}, first ${clip.first}; ` +
        `${different} pixels differ between frames 0 and ${last}, vertices move up to ` +
        `${largest.toFixed(0)} px; play reached frame ${playing[1]} in 0.5 s`;
  },

  // A clip's last frame: garment vertices seen from the camera are drawn where that frame
  // poses them, in the colour of their distance to the avatar posed with them.
  async 'frame-pixels'(browser, url, options) {
    return garmentPixels(browser, url, options, async (page) => {
      const last = await page.evaluate(() => window.grView.frameCount - 1);
      expect(last > 0, 'the page has no clip');
      await page.evaluate((f) => window.grView.setFrame(f), last);
    });
  },

  // The ease colour mode: the box switches the garment to the ease map and its legend.
  async 'ease-pixels'(browser, url, options) {
    return garmentPixels(browser, url, options, async (page) => {
      expect(await page.locator('#gr-legend-ease').isHidden(), 'the ease legend shows before the box');
      await page.locator('#gr-ease').check();
      expect(await page.locator('#gr-legend-ease').isVisible(), 'the ease legend does not show');
      expect(await page.locator('#gr-legend').isHidden(), 'the distance legend still shows');
    });
  },
};

// Each shape's garment vertices in view are drawn in the colour the page gave them, after
// `prepare(page)` has set the page up.
async function garmentPixels(browser, url, options, prepare) {
  const { page } = await openReport(browser, url);
  await prepare(page);
  const count = await page.evaluate(() => window.grView.shapeCount);
  const summary = [];
  for (let shape = 0; shape < count; ++shape) {
    await page.evaluate((s) => window.grView.setShape(s), shape);
    const probes = await page.evaluate(() => {
      const out = [];
      const n = window.grView.vertexCount(0);
      const stride = Math.max(1, Math.floor(n / 600));
      for (let v = 0; v < n; v += stride) {
        const p = window.grView.probe(0, v);
        if (p.visible && !p.flagged) out.push({ v, ...p });
      }
      return out;
    });
    const box = await page.locator('#gr-view canvas').boundingBox();
    const inside = probes.filter((p) => p.x > box.x + 3 && p.y > box.y + 3 &&
                                        p.x < box.x + box.width - 3 && p.y < box.y + box.height - 3);
    expect(inside.length >= 10, `shape ${shape}: only ${inside.length} garment vertices in view`);
    const png = await page.screenshot();
    if (options.screenshot) writeFileSync(options.screenshot.replace(/\.png$/, `_shape${shape}.png`), png);
    const colours = await analysePngs(browser, [png], coloursAround, inside.map(({ x, y }) => ({ x, y })));
    const misses = inside.filter((p, i) => !colours[i].some((c) => sameHue(c, p.colour)));
    expect(misses.length <= 0.1 * inside.length,
           `shape ${shape}: ${misses.length} of ${inside.length} garment points not in their colour, e.g. ` +
           misses.slice(0, 3).map((p) => `vertex ${p.v} at (${p.x.toFixed(0)}, ${p.y.toFixed(0)}) wants ` +
             `rgb(${p.colour}) sees rgb(${colours[inside.indexOf(p)][4]})`).join('; '));
    summary.push(`shape ${shape}: ${inside.length - misses.length} of ${inside.length} points in their colour`);
  }
  return summary.join('; ');
}

const options = parseArguments(process.argv.slice(2));
const check = checks[options.check];
if (!check) {
  console.error(`unknown check ${options.check}; one of ${Object.keys(checks).join(', ')}`);
  process.exit(2);
}
const url = pathToFileURL(resolve(options.page)).href;
const browser = await launch();
try {
  console.log(`ok ${options.check}: ${await check(browser, url, options)}`);
} catch (error) {
  console.error(`FAILED ${options.check} on ${url}: ${error.message}`);
  process.exitCode = 1;
} finally {
  await browser.close();
}
