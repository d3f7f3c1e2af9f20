// Drives the web page (web/index.html) in headless Chromium for the tests
// (test/test_web.ml) and for `make web-screenshot`, as test/window_session.sh
// drives the window: it runs steps and writes what it saw into a directory.
//
//   node drive.js PAGE OUTDIR STEP...
//
// PAGE is the path of index.html, optionally followed by #hold (frames then
// advance only through `advance`). Steps, in order:
//   wait              wait until the frame is finished
//   shot:NAME         NAME.ppm (the canvas, binary PPM), NAME.scene (the scene
//                     shown), NAME.json (the page's state)
//   keys:K1,K2,...    focus the canvas and press keys (Playwright names:
//                     ArrowLeft, Shift+D, a, Plus ...), each followed by wait
//   drag:X,Y,DX,DY    press the mouse button at canvas pixel (X, Y), move it by
//                     (DX, DY) in one event, release it; then wait
//   edit:FILE         replace the editor's text by FILE's
//   set:FILE          the same, at once (an input event, without Playwright's
//                     checks of the element: many times quicker)
//   parse:LIST        for each file named in the file LIST (one per line), put
//                     its text in the editor; OUTDIR/parse-I.txt is the text the
//                     editor then holds (textareas turn CRLF into LF),
//                     OUTDIR/parse-I.err the error shown ("" if none)
//   type:TEXT         type TEXT at the end of the editor, key by key
//   select:ID=VALUE   choose VALUE in the select #ID
//   advance:N         trace N bands (with #hold)
//   release           let frames advance by themselves again
//   probe:NAME        until the frame is finished, ask the page its state
//                     every few ms; NAME.txt: one line per answer, "finished bands"
//   answers:NAME      for about two seconds, every 100 ms, time how long the
//                     page takes to answer (its state, read in its own
//                     thread); NAME.txt: one line per answer, "MS finished
//                     SECONDS", the last the longest slice of the frame so far
//   download:NAME     click the download link; NAME.png is what it gives
//   savekey:NAME      press s on the canvas; NAME.png is the download it starts
//   screenshot:FILE   a PNG of the page
// Exit status: 0 done, 1 a step failed, 2 Chromium could not be started.
'use strict';
const fs = require('fs');
const path = require('path');

function fail(code, msg) {
  process.stderr.write(`drive.js: ${msg}\n`);
  process.exit(code);
}

const [pageArg, outDir, ...steps] = process.argv.slice(2);
if (!pageArg || !outDir) fail(1, 'usage: node drive.js PAGE OUTDIR STEP...');
const hash = pageArg.includes('#') ? pageArg.slice(pageArg.indexOf('#')) : '';
const url = 'file://' + path.resolve(pageArg.replace(/#.*$/, '')) + hash;

let chromium;
try {
  ({ chromium } = require('playwright-core'));
} catch (e) {
  fail(2, `playwright-core is not installed (make deps runs npm ci in test/web): ${e.message}`);
}

const state = (page) => page.evaluate(() => window.raytrace.state());

async function waitFinished(page) {
  await page.waitForFunction(() => window.raytrace && window.raytrace.state().finished, null,
    { timeout: 180000, polling: 20 });
}

async function shot(page, name) {
  // The canvas's RGB bytes, base64 in one string: an array of numbers
  // would cross the DevTools protocol as megabytes of JSON.
  const { w, h, rgb } = await page.evaluate(() => {
    const c = document.getElementById('canvas');
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    let s = '';
    const chunk = [];
    for (let i = 0; i < d.length; i += 4) {
      chunk.push(d[i], d[i + 1], d[i + 2]);
      if (chunk.length >= 3 * 8192) { s += String.fromCharCode.apply(null, chunk); chunk.length = 0; }
    }
    s += String.fromCharCode.apply(null, chunk);
    return { w: c.width, h: c.height, rgb: btoa(s) };
  });
  const header = Buffer.from(`P6\n${w} ${h}\n255\n`);
  fs.writeFileSync(path.join(outDir, name + '.ppm'), Buffer.concat([header, Buffer.from(rgb, 'base64')]));
  const s = await state(page);
  fs.writeFileSync(path.join(outDir, name + '.scene'), s.shown);
  fs.writeFileSync(path.join(outDir, name + '.json'), JSON.stringify(s, null, 1));
}

async function run(page, step) {
  const i = step.indexOf(':');
  const [verb, arg] = i < 0 ? [step, ''] : [step.slice(0, i), step.slice(i + 1)];
  switch (verb) {
    case 'wait': return waitFinished(page);
    case 'shot': return shot(page, arg);
    case 'keys':
      await page.focus('#canvas');
      for (const k of arg.split(',')) {
        await page.keyboard.press(k);
        await waitFinished(page);
      }
      return;
    case 'drag': {
      const [x, y, dx, dy] = arg.split(',').map(Number);
      const box = await page.locator('#canvas').boundingBox();
      await page.mouse.move(box.x + x, box.y + y);
      await page.mouse.down();
      await page.mouse.move(box.x + x + dx, box.y + y + dy, { steps: 1 });
      await page.mouse.up();
      return waitFinished(page);
    }
    case 'edit': return page.fill('#scene', fs.readFileSync(arg, 'utf8'));
    case 'set':
      return page.evaluate((text) => {
        const e = document.getElementById('scene');
        e.value = text;
        e.dispatchEvent(new Event('input'));
      }, fs.readFileSync(arg, 'utf8'));
    case 'parse': {
      const files = fs.readFileSync(arg, 'utf8').split('\n').filter((f) => f !== '');
      const texts = files.map((f) => fs.readFileSync(f, 'utf8'));
      const results = await page.evaluate((texts) => texts.map((text) => {
        const e = document.getElementById('scene');
        e.value = text;
        e.dispatchEvent(new Event('input'));
        return [e.value, document.getElementById('error').textContent];
      }), texts);
      results.forEach(([text, error], i) => {
        fs.writeFileSync(path.join(outDir, `parse-${i}.txt`), text);
        fs.writeFileSync(path.join(outDir, `parse-${i}.err`), error);
      });
      return;
    }
    case 'type':
      await page.focus('#scene');
      await page.keyboard.press('Control+End');
      return page.keyboard.type(arg);
    case 'select': {
      const [id, value] = arg.split('=');
      return page.selectOption('#' + id, value, { timeout: 5000 });
    }
    case 'advance': return page.evaluate((n) => window.raytrace.advance(n), Number(arg));
    case 'release': return page.evaluate(() => window.raytrace.hold(false));
    case 'probe': {
      const lines = [];
      for (;;) {
        const s = await state(page);
        lines.push(`${s.finished} ${s.bands}`);
        if (s.finished) break;
        await new Promise((r) => setTimeout(r, 5));
      }
      fs.writeFileSync(path.join(outDir, arg + '.txt'), lines.join('\n') + '\n');
      return;
    }
    case 'answers': {
      const lines = [];
      for (let i = 0; i < 20; i++) {
        const t0 = Date.now();
        const s = await state(page);
        lines.push(`${Date.now() - t0} ${s.finished} ${s.sliceSoFar}`);
        await new Promise((r) => setTimeout(r, 100));
      }
      fs.writeFileSync(path.join(outDir, arg + '.txt'), lines.join('\n') + '\n');
      return;
    }
    case 'download':
    case 'savekey': {
      const start = verb === 'download' ? page.click('#download')
        : page.focus('#canvas').then(() => page.keyboard.press('s'));
      const [dl] = await Promise.all([page.waitForEvent('download', { timeout: 30000 }), start]);
      return dl.saveAs(path.join(outDir, arg + '.png'));
    }
    case 'screenshot': return page.screenshot({ path: arg, fullPage: true });
    default: throw new Error(`unknown step ${step}`);
  }
}

(async () => {
  let browser;
  try {
    browser = await chromium.launch({
      executablePath: process.env.RAYTRACE_CHROMIUM || '/usr/bin/chromium',
      args: ['--headless', '--no-sandbox', '--disable-gpu'],
    });
  } catch (e) {
    fail(2, `cannot start Chromium: ${e.message.split('\n')[0]}`);
  }
  try {
    const page = await browser.newPage({ viewport: { width: 1400, height: 900 }, acceptDownloads: true });
    const errors = [];
    page.on('pageerror', (e) => errors.push(e.message));
    await page.goto(url);
    await page.waitForFunction(() => window.raytrace !== undefined, null, { timeout: 30000 });
    for (const step of steps) {
      await run(page, step);
      if (errors.length) throw new Error(`the page raised: ${errors.join('; ')}`);
    }
    await browser.close();
  } catch (e) {
    await browser.close();
    fail(1, e.message);
  }
})();
