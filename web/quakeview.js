// QuakeView page shell: loads the engine (quakeview-engine.js/.wasm) with a progress bar, shows
// fatal errors on the page, and defines the scriptable API `window.quakeview`.
//
// API (kept for the life of the product; later versions only add members):
//   ready      Promise: resolves after the first frame in which everything of the initial view has
//              loaded or failed; rejects with an Error carrying the on-page message when WebGL2 is
//              unavailable or the engine cannot start.
//   stats()    {fps, frameMs: {cull, lod, animate, upload, render, total}, drawCalls, triangles,
//              buildings: {loaded, visible, animated}, tiles: {loaded, pending, failed}, heapBytes,
//              heapReservedBytes, uploadBytes, timeSeconds} — medians over recent frames; extensions:
//              softwareRenderer, renderer, antialias, maxPixelRatio, quality, governor, qualityStep;
//              pixels (drawing buffer width x height this frame), samples (pixels x the MSAA
//              samples per pixel, = pixels without antialiasing), lastFrame: {triangles, drawCalls,
//              ui: {vertices, triangles, drawCalls, uploadBytes, cached, redrawn, copiedPixels,
//              redraws, staleFrames}} of this frame alone (ui: the panels', drawn after the city
//              and not in its counts, through a kept picture redrawn when they change);
//              canvas: {width, height (drawing buffer, device px), cssWidth, cssHeight, pixelRatio
//              (buffer px per CSS px: the device's, at most 2, 1.5 on screens under 600 CSS px wide,
//              lower while frames are slow), devicePixelRatio (the device's own)}.
//   errors()   the message strings the UI shows.
//   uiText()   the text of the panels and windows currently shown.
//   uiOutline()  extension: the same as headings, {revision, sections: [{heading, lines}]}, the
//              source of the page's accessible copy (#qv-panel); revision grows when it changes.
//   uiFocus()  extension: the control showing the keyboard focus ("Export CSV, button"), or null.
//   uiLayout() extension: where the windows and their controls are (see below).
//   getCamera() {x, y, distance, headingDeg, pitchDeg, fovDeg} (metres east/north of the origin).
//   worldToScreen(x, y, z) [px, py] CSS pixels of a city-frame point, or null.
//   setCamera(c)  any subset of getCamera()'s fields; false when a value was invalid.
//   setTime(s), time(), duration(), play(), pause(), playing()
//   pick(x, y), building(id), select(id), selection()   picking and the selected building
//   consequences()   totals of the city, the view and each district, and the shaking's provenance
//   setFilters({minDamage, minProbability: {state, percent}, use, criticalOnly, categories}), filters(),
//   setLodVisibility({lod1, lod2}),
//              use: one normalized use or several joined by '+' ('hospital+school'); criticalOnly:
//              essential facilities, schools and shelters; categories: an array of 'essential',
//              'school_shelter', 'high_occupancy', 'hazardous' (a building passes with any).
//   lodVisibility(), setAmplitude(x), amplitude(), setColorMode('drift' | 'peak' | 'damage' |
//   'neutral' | 'p-moderate' | 'expected-damage' | 'tag'), colorMode(), shownColorMode(), search(query), filteredList(limit),
//   exportList('csv' | 'geojson'), flyToSelection()     extensions used by the panel's actions
//   report()   a Promise of the situation report: one print-ready HTML document (the event, headline
//              numbers with 90 % intervals, impact level, map, HAZUS tables, facilities, casualties
//              at 2 AM / 2 PM / 5 PM, districts, limits and sources), the same as `quakeview-prep
//              report` writes; it resolves once the city's index and totals have loaded (rejects
//              after 120 s or without a city). saveReport() downloads it (the panel's "Report").
//   screenshot()  the view as a PNG data URL with its caption (event, city, attribution); saveImage()
//              downloads it (the panel's "Save image")
//   benchResult  with ?bench=SECONDS: {seconds, frames, fps, frameMs: {cull, lod, animate, upload,
//              render, total}, drawCalls, triangles}, each but seconds/frames as {median, p95};
//              null until the flight ends (benchDone: a Promise of it).
(function () {
  'use strict';

  const canvas = document.getElementById('canvas');
  const loading = document.getElementById('loading');
  const loadingFill = loading.querySelector('.loading-fill');
  const loadingLabel = loading.querySelector('.loading-label');
  const errorBox = document.getElementById('error');
  const outlineBox = document.getElementById('qv-outline');
  const statusBox = document.getElementById('qv-status');
  const focusBox = document.getElementById('qv-focus');
  const params = new URLSearchParams(window.location.search);

  let resolveReady;
  let rejectReady;
  const ready = new Promise((resolve, reject) => { resolveReady = resolve; rejectReady = reject; });
  // A rejection nobody awaits must not become an "unhandled rejection" console error.
  ready.catch(() => {});

  let engine = null;
  // qv::ColorMode 0 … 6
  const COLOR_MODES = ['drift', 'peak', 'damage', 'neutral', 'p-moderate', 'expected-damage', 'tag'];
  const shellErrors = [];

  function setProgress(fraction, label) {
    const percent = Math.max(0, Math.min(100, Math.round(fraction * 100)));
    loadingFill.style.width = percent + '%';
    loading.setAttribute('aria-valuenow', String(percent));
    if (label) loadingLabel.textContent = label;
  }

  function fatal(message) {
    loading.hidden = true;
    errorBox.textContent = message;
    errorBox.hidden = false;
    shellErrors.push(message);
    rejectReady(new Error(message));
  }

  function callString(name) {
    if (!engine) return null;
    return engine.UTF8ToString(engine['_' + name]());
  }

  const api = {
    ready,
    stats() {
      const text = callString('qv_stats_json');
      if (!text) return null;
      const stats = JSON.parse(text);
      // Extension: the canvas's drawing buffer (device pixels, as the engine capped the ratio) and
      // its size on the page (CSS pixels).
      stats.canvas = {
        width: canvas.width,
        height: canvas.height,
        cssWidth: canvas.clientWidth,
        cssHeight: canvas.clientHeight,
        pixelRatio: canvas.clientWidth > 0 ? canvas.width / canvas.clientWidth : 1,
        devicePixelRatio: window.devicePixelRatio || 1,
      };
      return stats;
    },
    errors() {
      const text = callString('qv_errors_json');
      return shellErrors.concat(text ? JSON.parse(text) : []);
    },
    uiText() {
      return callString('qv_ui_text') || '';
    },
    uiOutline() {
      const text = callString('qv_ui_outline_json');
      return text ? JSON.parse(text) : null;
    },
    uiFocus() {
      return callString('qv_ui_focus') || null;
    },
    // Extension: where the panels are, for pointing at a control (a tap on a touch screen):
    // {windows: [{title, x, y, width, height, collapsed}], items: [{window, label, x, y, width,
    // height}]} in CSS pixels from the canvas's top-left corner, as drawn in the last frame; items
    // are the buttons, section headers and checkboxes, by their visible labels.
    uiLayout() {
      const text = callString('qv_ui_layout');
      return text ? JSON.parse(text) : null;
    },
    // Extension: where a city-frame point [x, y, z] (metres from the tileset origin) appears on
    // the canvas, in CSS pixels from its top-left corner; null when behind the camera.
    worldToScreen(x, y, z = 0) {
      if (!engine) return null;
      return JSON.parse(engine.UTF8ToString(engine._qv_world_to_screen(Number(x), Number(y), Number(z))));
    },
    getCamera() {
      const text = callString('qv_get_camera_json');
      return text ? JSON.parse(text) : null;
    },
    // Takes any subset of getCamera()'s fields; returns false (and keeps the previous value of a
    // field) when a given value is not a finite number or out of range.
    setCamera(c) {
      if (!engine || !c || typeof c !== 'object') return false;
      const current = api.getCamera();
      const keys = ['x', 'y', 'distance', 'headingDeg', 'pitchDeg', 'fovDeg'];
      let valid = true;
      const v = keys.map((k) => {
        if (!(k in c)) return current[k];
        const n = typeof c[k] === 'number' ? c[k] : NaN;
        if (!Number.isFinite(n)) valid = false;
        return n;
      });
      const accepted = engine._qv_set_camera(...v) === 1;
      return valid && accepted;
    },
    setTime(seconds) {
      return !!engine && typeof seconds === 'number' && engine._qv_set_time(seconds) === 1;
    },
    time() { return engine ? engine._qv_time() : 0; },
    duration() { return engine ? engine._qv_duration() : 0; },
    play() { if (engine) engine._qv_play(); },
    pause() { if (engine) engine._qv_pause(); },
    playing() { return !!engine && engine._qv_playing() === 1; },
    benchResult: null,

    // Picking and inspection. A building object: {id, name, use, address, x, y, heightM,
    // heightSource, storeys, storeysSource, structuralType, codeEra, importance, lod, damageState,
    // peakDriftRatio: [per storey], peakRoofDisplacementM, pgaG} (x, y: the footprint centre in
    // metres east and north of the tileset origin, the frame of getCamera()).
    pick(x, y) {
      if (!engine) return null;
      return JSON.parse(engine.UTF8ToString(engine._qv_pick(Number(x), Number(y))));
    },
    building(id) {
      if (!engine || typeof id !== 'string') return null;
      return JSON.parse(engine.ccall('qv_building', 'string', ['string'], [id]));
    },
    // The consequences' totals (city, view, districts) and the shaking's provenance; null without
    // results. Shape in the README's table.
    consequences() {
      if (!engine) return null;
      return JSON.parse(engine.ccall('qv_consequences', 'string', [], []));
    },
    select(id) {
      if (!engine || typeof id !== 'string') return false;
      return engine.ccall('qv_select', 'number', ['string'], [id]) === 1;
    },
    selection() {
      const id = callString('qv_selection');
      return id ? id : null;
    },
    // Extensions: fly to the selection; filters; search; the filtered list and its export.
    flyToSelection() { return !!engine && engine._qv_fly_to_selection() === 1; },
    setFilters(f) {
      if (!engine || !f || typeof f !== 'object') return false;
      const states = ['none', 'slight', 'moderate', 'extensive', 'complete'];
      let minDamage = -1;
      if (typeof f.minDamage === 'number') minDamage = f.minDamage;
      else if (typeof f.minDamage === 'string') minDamage = states.indexOf(f.minDamage);
      const categories = Array.isArray(f.categories) ? f.categories.filter((c) => typeof c === 'string').join('+') : '';
      // minProbability: {state: 'moderate' (or 1..4), percent: 10}: P(>= state) at least 10 %.
      let pState = -1;
      let pPercent = 0;
      const p = f.minProbability;
      if (p && typeof p === 'object') {
        pState = typeof p.state === 'number' ? p.state : states.indexOf(p.state);
        pPercent = typeof p.percent === 'number' ? Math.round(p.percent) : 0;
      }
      return engine.ccall('qv_set_filters', 'number', ['number', 'string', 'number', 'string', 'number', 'number'],
        [minDamage, typeof f.use === 'string' ? f.use : '', f.criticalOnly ? 1 : 0, categories, pState, pPercent]) === 1;
    },
    filters() {
      const text = callString('qv_filters_json');
      return text ? JSON.parse(text) : null;
    },
    // Amplitude exaggeration of the displayed motion (1 … 200, as the panel's slider).
    setAmplitude(x) {
      return !!engine && typeof x === 'number' && engine._qv_set_amplitude(x) === 1;
    },
    amplitude() { return engine ? engine._qv_amplitude() : null; },
    // Colour mode: 'drift' (current inter-storey drift), 'peak' (peak drift), 'damage', 'neutral',
    // 'p-moderate' (P(damage >= moderate)), 'expected-damage', 'tag' (most likely inspection tag).
    setColorMode(name) {
      const mode = COLOR_MODES.indexOf(name);
      return !!engine && mode >= 0 && engine._qv_set_color_mode(mode) === 1;
    },
    colorMode() { return engine ? COLOR_MODES[engine._qv_color_mode()] || null : null; },
    // The mode the city is drawn in now: colorMode(), except 'p-moderate' once the shaking is over
    // (at the end of the record, in the 'drift' mode, for results with damage probabilities).
    shownColorMode() { return engine ? COLOR_MODES[engine._qv_shown_color_mode()] || null : null; },
    // LOD1 (extruded footprints) and LOD2 (detailed models) shown or hidden; either key may be left out.
    setLodVisibility(v) {
      if (!engine || !v || typeof v !== 'object') return false;
      const now = api.lodVisibility() || { lod1: true, lod2: true };
      const lod1 = typeof v.lod1 === 'boolean' ? v.lod1 : now.lod1;
      const lod2 = typeof v.lod2 === 'boolean' ? v.lod2 : now.lod2;
      return engine._qv_set_lod_visibility(lod1 ? 1 : 0, lod2 ? 1 : 0) === 1;
    },
    lodVisibility() {
      const text = callString('qv_lod_visibility_json');
      return text ? JSON.parse(text) : null;
    },
    search(query, limit = 20) {
      if (!engine || typeof query !== 'string') return [];
      return JSON.parse(engine.ccall('qv_search', 'string', ['string', 'number'], [query, limit]));
    },
    searchReady() { return !!engine && engine._qv_search_ready() === 1; },
    filteredList(limit = 100) {
      if (!engine) return null;
      return JSON.parse(engine.UTF8ToString(engine._qv_filtered_json(limit)));
    },
    // Downloads the filtered list ("csv" or "geojson") as the panel's Export buttons do; returns
    // its text. The downloaded CSV file starts with a UTF-8 byte-order mark for spreadsheets; the
    // returned string does not (a JavaScript string has no byte order).
    exportList(format = 'csv') {
      if (!engine) return '';
      return engine.ccall('qv_export', 'string', ['string'], [format]).replace(/^\uFEFF/, '');
    },
    // The picture of the view as a PNG data URL: the canvas as drawn (panels, colour key and scale
    // bar included; a frame drawn now and read in the same task) with a caption band under it: the
    // shaking (SCENARIO or ACTUAL) and the earthquake, the city, the time and the filters, the
    // method and the attribution (qv::imageCaption). null before a city is loaded.
    screenshot() {
      if (!engine) return null;
      const caption = JSON.parse(engine.UTF8ToString(engine._qv_image_caption()));
      if (!caption) return null;
      engine._qv_draw_now();  // the drawing buffer is not kept: draw the frame and read it in this task
      const scale = canvas.clientWidth > 0 ? canvas.width / canvas.clientWidth : 1;
      const fontPx = Math.round(13 * scale);
      const lineHeight = Math.round(fontPx * 1.45);
      const pad = Math.round(8 * scale);
      const out = document.createElement('canvas');
      out.width = canvas.width;
      out.height = canvas.height + caption.lines.length * lineHeight + 2 * pad;
      const g = out.getContext('2d');
      g.drawImage(canvas, 0, 0);
      g.fillStyle = '#f4f2ee';
      g.fillRect(0, canvas.height, out.width, out.height - canvas.height);
      g.textBaseline = 'top';
      caption.lines.forEach((line, i) => {
        g.font = `${i === 0 ? 'bold ' : ''}${fontPx}px sans-serif`;
        g.fillStyle = i === 0 ? (caption.actual ? '#b00d00' : '#8c4000') : '#222222';
        g.fillText(line, pad, canvas.height + pad + i * lineHeight, out.width - 2 * pad);
      });
      return out.toDataURL('image/png');
    },
    // The situation report's HTML (see the header). The engine answers "" while the files it rests
    // on are loading.
    report() {
      return new Promise((resolve, reject) => {
        const started = Date.now();
        const poll = () => {
          const html = engine ? engine.UTF8ToString(engine._qv_report()) : '';
          if (html) { resolve(html); return; }
          if (Date.now() - started > 120000) {
            reject(new Error(engine ? 'the situation report waited 120 s for the city index and totals'
              : 'no city is loaded, so there is no situation report'));
            return;
          }
          setTimeout(poll, 100);
        };
        poll();
      });
    },
    // Downloads report() as an HTML file named for the city and the event; resolves with the name.
    async saveReport() {
      const html = await this.report();
      const name = JSON.parse(engine.UTF8ToString(engine._qv_image_caption())).fileName.replace(/-view\.png$/, '-report.html');
      const link = document.createElement('a');
      link.href = URL.createObjectURL(new Blob([html], { type: 'text/html' }));
      link.download = name;
      document.body.appendChild(link);
      link.click();
      setTimeout(() => { URL.revokeObjectURL(link.href); link.remove(); }, 1000);
      return name;
    },
    // Downloads screenshot() as a PNG named for the city, the event and the view (the panel's
    // "Save image"); returns the file name, or null before a city is loaded.
    saveImage() {
      const url = this.screenshot();
      if (!url) return null;
      const name = JSON.parse(engine.UTF8ToString(engine._qv_image_caption())).fileName;
      const link = document.createElement('a');
      link.href = url;
      link.download = name;
      document.body.appendChild(link);
      link.click();
      link.remove();
      return name;
    },
  };
  Object.defineProperty(window, 'quakeview', { value: api, writable: false, configurable: false });

  // Right-click "Save image as" / "Copy image" give the view, not a blank picture. The drawing
  // buffer is not kept between frames (Browser.cpp: keeping it costs frames on software
  // renderers), so a browser saving the canvas itself would read a cleared buffer. At a right-button
  // press on the canvas the page draws the frame and lays its picture over the canvas
  // (#qv-snapshot, exactly the canvas's size and place), and the context menu that follows (at
  // the press on Linux and macOS, at the release on Windows) is the picture's. A right-drag still
  // orbits: at the first move with the button held the picture goes and the canvas takes the
  // pointer; a menu after a drag (Windows) is not shown. The picture goes when the pointer moves
  // without a button, at the next press or wheel turn, or at a key.
  const snapshot = document.createElement('img');
  snapshot.id = 'qv-snapshot';
  snapshot.alt = 'Picture of the city view';
  snapshot.draggable = false;
  snapshot.hidden = true;
  document.body.appendChild(snapshot);
  let rightPress = null; // {x, y, dragged} of the right button's press on the canvas
  function hideSnapshot() {
    if (snapshot.hidden) return;
    snapshot.hidden = true;
    snapshot.removeAttribute('src');
  }
  canvas.addEventListener('mousedown', (e) => {
    if (e.button !== 2) { hideSnapshot(); return; }
    rightPress = { x: e.clientX, y: e.clientY, dragged: false };
    if (!engine) return;
    engine._qv_draw_now(); // the frame drawn now and read in this task, as screenshot() does
    const r = canvas.getBoundingClientRect();
    Object.assign(snapshot.style, { left: `${r.left}px`, top: `${r.top}px`, width: `${r.width}px`, height: `${r.height}px` });
    snapshot.src = canvas.toDataURL('image/png');
    snapshot.hidden = false;
  });
  snapshot.addEventListener('pointermove', (e) => {
    if ((e.buttons & 2) === 0) { hideSnapshot(); return; }
    // A right-drag: the canvas takes the pointer (its mouse events follow) and orbits.
    if (rightPress) rightPress.dragged = true;
    hideSnapshot();
    try { canvas.setPointerCapture(e.pointerId); } catch (err) { /* the press has ended */ }
  });
  canvas.addEventListener('pointermove', (e) => {
    if (rightPress && (e.buttons & 2) !== 0 && Math.hypot(e.clientX - rightPress.x, e.clientY - rightPress.y) > 4) {
      rightPress.dragged = true;
    }
  });
  canvas.addEventListener('contextmenu', (e) => {
    if (rightPress && rightPress.dragged) e.preventDefault(); // after an orbit, no menu
  });
  snapshot.addEventListener('mousedown', (e) => { if (e.button !== 2) hideSnapshot(); });
  snapshot.addEventListener('wheel', hideSnapshot, { passive: true });
  window.addEventListener('keydown', hideSnapshot, true);
  window.addEventListener('mouseup', (e) => {
    // (rightPress stays until the next press: on Windows the menu's event follows the release.)
    if (e.button === 2 && rightPress && rightPress.dragged) hideSnapshot();
  });
  // Extension for tests: whether the view's picture lies over the canvas (a right-button press).
  api.snapshotShown = () => !snapshot.hidden;

  // Printing the page prints the situation report (report(), when the city's index and totals have
  // loaded) and, on a page after it, the view's picture with its caption (screenshot()), never a
  // black canvas: a WebGL canvas is printed from its drawing buffer, which is not kept. Before the
  // print both are put in the canvas's place (print CSS in quakeview.css); after it the canvas is
  // drawn again at the window's size (a frame drawn during the print would otherwise leave the
  // drawing buffer at the paper's size until the next frame).
  const printReport = document.createElement('div');
  printReport.id = 'qv-print-report';
  document.body.appendChild(printReport);
  const printPicture = document.createElement('img');
  printPicture.id = 'qv-print';
  printPicture.alt = 'The city view with its caption';
  document.body.appendChild(printPicture);
  // The report's content without its <html> shell; its styles (scoped to .qv-report) join the page
  // as a constructed style sheet, which a Content Security Policy without 'unsafe-inline' allows.
  let reportSheet = null;
  function reportNodes(html) {
    // The <style> element is cut out of the text before parsing (a parsed one would be refused by
    // the policy, with a console error, even in a parsed document that is never shown).
    const open = html.indexOf('<style>');
    const close = html.indexOf('</style>', open);
    const css = open >= 0 && close > open ? html.slice(open + '<style>'.length, close) : '';
    const body = open >= 0 && close > open ? html.slice(0, open) + html.slice(close + '</style>'.length) : html;
    const doc = new DOMParser().parseFromString(body, 'text/html');
    try {
      if (!reportSheet) {
        reportSheet = new CSSStyleSheet();
        document.adoptedStyleSheets = [...document.adoptedStyleSheets, reportSheet];
      }
      reportSheet.replaceSync(css);
    } catch (e) {
      console.warn('The situation report prints without its styles: ' + e.message);
    }
    const content = doc.querySelector('.qv-report');
    return content ? [document.importNode(content, true)] : [];
  }
  window.addEventListener('beforeprint', () => {
    const html = engine ? engine.UTF8ToString(engine._qv_report()) : '';
    printReport.replaceChildren(...(html ? reportNodes(html) : []));
    const url = api.screenshot();
    if (url) printPicture.src = url;
    document.body.classList.toggle('qv-printing', !!url || !!html);
  });
  window.addEventListener('afterprint', () => {
    document.body.classList.remove('qv-printing');
    printPicture.removeAttribute('src');
    printReport.replaceChildren();
    if (engine) engine._qv_draw_now();
  });
  let resolveBench;
  // Extension: resolves with benchResult when a ?bench=SECONDS flight ends.
  api.benchDone = new Promise((resolve) => { resolveBench = resolve; });

  // The accessible copy of the panels beside the canvas (#qv-panel, visually hidden): the engine's
  // outline as headings and lists, rewritten only when its revision changes and then only the
  // elements whose text changed, so a screen reader's reading position survives. Two polite live
  // regions announce selection changes and errors (#qv-status) and the control that takes the
  // keyboard focus (#qv-focus).
  const DAMAGE_WORDS = { none: 'no damage', slight: 'slight damage', moderate: 'moderate damage',
    extensive: 'extensive damage', complete: 'complete damage' };
  const access = { revision: -1, selection: null, pending: null, tries: 0, errors: 0, focus: null };

  function setText(element, text) {
    if (element.textContent !== text) element.textContent = text;
  }

  function renderOutline(outline) {
    const sections = outline.sections || [];
    while (outlineBox.children.length > sections.length) outlineBox.lastElementChild.remove();
    sections.forEach((section, i) => {
      let block = outlineBox.children[i];
      if (!block) {
        block = document.createElement('div');
        block.appendChild(document.createElement('h2'));
        block.appendChild(document.createElement('ul'));
        outlineBox.appendChild(block);
      }
      setText(block.firstElementChild, section.heading);
      const list = block.lastElementChild;
      const lines = section.lines || [];
      while (list.children.length > lines.length) list.lastElementChild.remove();
      lines.forEach((line, j) => {
        let item = list.children[j];
        if (!item) {
          item = document.createElement('li');
          list.appendChild(item);
        }
        setText(item, line);
      });
    });
  }

  function announceSelection(id) {
    // A building selected from the search may have no loaded tile yet, and a far-view tile may not
    // carry its name: the search index names it.
    const loaded = api.building(id);
    const hit = api.search(id, 5).find((entry) => entry.id === id);
    const label = (loaded && (loaded.name || loaded.address)) || (hit && (hit.name || hit.address));
    if (!label && ++access.tries < 40) return false;  // not known yet: ask again
    const b = loaded || hit;
    const name = label || id;
    const damage = b ? (DAMAGE_WORDS[b.damageState] || 'no earthquake result') : 'details loading';
    setText(statusBox, 'Selected: ' + name + ', ' + damage);
    return true;
  }

  function updateAccessibility() {
    if (!engine) return;
    const revision = engine._qv_ui_outline_revision();
    if (revision !== access.revision) {
      const outline = api.uiOutline();
      if (outline) {
        access.revision = revision;
        renderOutline(outline);
      }
    }
    const selection = api.selection();
    if (selection !== access.selection) {
      access.selection = selection;
      access.pending = selection;
      access.tries = 0;
      if (selection === null) setText(statusBox, 'Selection cleared');
    }
    if (access.pending !== null && announceSelection(access.pending)) access.pending = null;
    const errors = api.errors();
    if (errors.length < access.errors) access.errors = 0;
    if (errors.length > access.errors) {
      setText(statusBox, 'Error: ' + errors[errors.length - 1]);
      access.errors = errors.length;
    }
    const focus = api.uiFocus();
    if (focus !== access.focus) {
      access.focus = focus;
      if (focus) setText(focusBox, focus);
    }
  }

  // WebGL2 first: without it the engine cannot draw, and the user should read why at once.
  const probe = document.createElement('canvas');
  const gl = probe.getContext('webgl2');
  if (!gl) {
    fatal('WebGL2 is not available in this browser or on this device, so the city cannot be drawn. ' +
          'Use a current Chrome, Edge, Firefox or Safari with hardware acceleration enabled.');
    return;
  }
  // The renderer's name: a software rasterizer (SwiftShader, WARP, llvmpipe) makes the engine start
  // in its weak-device preset. Chromium masks RENDERER ("WebKit WebGL") and names the real one
  // through WEBGL_debug_renderer_info; Firefox answers RENDERER directly (and deprecates the
  // extension, so it is asked only when needed).
  let renderer = String(gl.getParameter(gl.RENDERER) || '');
  if (/^WebKit WebGL$/i.test(renderer) || renderer === '') {
    const info = gl.getExtension('WEBGL_debug_renderer_info');
    if (info) renderer = String(gl.getParameter(info.UNMASKED_RENDERER_WEBGL) || renderer);
  }
  const lose = gl.getExtension('WEBGL_lose_context');
  if (lose) lose.loseContext();

  // Engine arguments from the page URL (the city's address is checked against the data origin
  // policy in start(), before anything of it is fetched).
  const args = [];
  if (params.get('scene')) args.push('--scene', params.get('scene'));
  if (params.get('aa') === '0') args.push('--no-antialias');
  if (params.get('aa') === '1') args.push('--antialias');
  if (params.get('quality')) args.push('--quality', params.get('quality'));
  if (renderer) args.push('--webgl-renderer', renderer);
  if (params.get('bench')) args.push('--bench', params.get('bench'));
  if (params.get('memory')) args.push('--memory-mb', params.get('memory'));

  // The shareable view lives in the URL hash: #cam=x,y,distance,heading,pitch,fov&t=seconds
  // &play=0|1&sel=id&f=minDamage,use,critical[,state:percent]. The engine validates every value (a malformed one falls
  // back to the default with a message).
  const hash = new URLSearchParams(window.location.hash.replace(/^#/, ''));
  if (hash.get('cam')) args.push('--camera', hash.get('cam'));
  if (hash.get('t')) args.push('--time', hash.get('t'));
  if (hash.get('sel')) args.push('--select', hash.get('sel'));
  // f= is read as written: its '+' joins uses and categories (URLSearchParams would make it a space).
  const rawFilters = /(?:^|&)f=([^&]*)/.exec(window.location.hash.replace(/^#/, ''));
  if (hash.get('f') && rawFilters && rawFilters[1]) {
    let text = rawFilters[1];
    try { text = decodeURIComponent(text); } catch (e) { /* malformed escapes: the engine reports the text */ }
    args.push('--filters', text);
  }
  if (hash.get('play')) args.push('--playing', hash.get('play'));

  function viewHash() {
    const c = api.getCamera();
    if (!c) return null;
    const round = (v, d) => Number(v.toFixed(d));
    const parts = ['cam=' + [round(c.x, 1), round(c.y, 1), round(c.distance, 1), round(c.headingDeg, 1),
      round(c.pitchDeg, 1), round(c.fovDeg, 1)].join(',')];
    parts.push('t=' + round(api.time(), 2));
    parts.push('play=' + (api.playing() ? 1 : 0));  // a link copied while paused opens paused
    const sel = api.selection();
    if (sel) parts.push('sel=' + encodeURIComponent(sel));
    const f = api.filters();
    const categories = f && Array.isArray(f.categories) ? f.categories : [];
    if (f && (f.minDamage || f.minProbability || f.use || f.criticalOnly || categories.length)) {
      const states = ['none', 'slight', 'moderate', 'extensive', 'complete'];
      const d = f.minDamage ? states.indexOf(f.minDamage) : '';
      // The critical field: "1" (essential, schools, shelters) or category names joined by '+'.
      let critical = f.criticalOnly ? '1' : '';
      if (categories.length) {
        const names = new Set(categories);
        if (f.criticalOnly) { names.add('essential'); names.add('school_shelter'); }
        critical = [...names].join('+');
      }
      const fields = [d, f.use, critical];
      // The fourth field only when set: links made before it keep their three fields.
      if (f.minProbability) fields.push(states.indexOf(f.minProbability.state) + ':' + f.minProbability.percent);
      parts.push('f=' + fields.join(','));
    }
    return parts.join('&');
  }
  function keepHash() {
    const h = viewHash();
    if (h !== null && '#' + h !== window.location.hash) {
      history.replaceState(null, '', window.location.pathname + window.location.search + '#' + h);
    }
  }

  // The data origin policy. A link can name any address in ?data=, but this site shows only data
  // from its own origin and from the origins its administrator lists in config.json beside
  // index.html: {"dataOrigins": ["https://data.example.org"]}. Otherwise a link to the official
  // viewer could show fabricated damage under the city's own address. A missing config.json
  // (HTTP 404) means "this site only"; a broken one is reported and also means "this site only".
  async function loadConfig() {
    const config = { dataOrigins: [], problems: [] };
    let response;
    try {
      response = await fetch('config.json', { cache: 'no-cache', credentials: 'same-origin' });
    } catch (e) {
      config.problems.push('config.json beside the page could not be read (' + e.message +
        '); only data from this site is loaded.');
      return config;
    }
    if (response.status === 404) return config;
    if (!response.ok) {
      config.problems.push('config.json beside the page answered HTTP ' + response.status +
        '; only data from this site is loaded.');
      return config;
    }
    let json;
    try {
      json = JSON.parse(await response.text());
    } catch (e) {
      config.problems.push('config.json beside the page is not valid JSON (' + e.message +
        '); only data from this site is loaded.');
      return config;
    }
    const list = json && typeof json === 'object' ? json.dataOrigins : undefined;
    if (list === undefined) return config;
    if (!Array.isArray(list)) {
      config.problems.push('config.json: "dataOrigins" must be a list of origins such as ' +
        '"https://data.example.org"; only data from this site is loaded.');
      return config;
    }
    for (const entry of list) {
      let origin = null;
      try {
        const url = new URL(String(entry));
        if ((url.protocol === 'https:' || url.protocol === 'http:') && url.origin === String(entry)) {
          origin = url.origin;
        }
      } catch {
        origin = null;
      }
      if (origin) {
        config.dataOrigins.push(origin);
      } else {
        config.problems.push('config.json: "dataOrigins" entry ' + JSON.stringify(entry) +
          ' is not an origin (scheme://host[:port], nothing after it, e.g. "https://data.example.org"); ignored.');
      }
    }
    return config;
  }

  // Download the .wasm ourselves to show progress, then hand the bytes to the engine.
  async function fetchWasm(url) {
    const response = await fetch(url);
    if (!response.ok) throw new Error('HTTP ' + response.status + ' for ' + url);
    const total = Number(response.headers.get('Content-Length')) || 0;
    if (!response.body || !total) return new Uint8Array(await response.arrayBuffer());
    const reader = response.body.getReader();
    const bytes = new Uint8Array(total);
    let received = 0;
    for (;;) {
      const { done, value } = await reader.read();
      if (done) break;
      if (received + value.length > total) throw new Error('more bytes than announced for ' + url);
      bytes.set(value, received);
      received += value.length;
      setProgress(received / total * 0.9, 'Loading QuakeView… ' + Math.round(received / 1024) + ' KB');
    }
    return bytes.subarray(0, received);
  }

  function loadScript(src) {
    return new Promise((resolve, reject) => {
      const script = document.createElement('script');
      script.src = src;
      script.onload = resolve;
      script.onerror = () => reject(new Error('could not load ' + src));
      document.head.appendChild(script);
    });
  }

  async function start() {
    setProgress(0.02, 'Loading QuakeView…');
    if (!params.get('scene')) {
      // The engine applies the policy (qv::dataOriginProblem) before it requests anything: it
      // gets the page's origin, the allowed ones and the origin the browser resolves ?data= to.
      const config = await loadConfig();
      for (const problem of config.problems) {
        console.warn(problem);
        args.push('--shell-error', problem);
      }
      const address = params.get('data') || 'data/default/tileset.json';
      args.push('--data', address, '--page-origin', window.location.origin);
      try {
        args.push('--data-origin', new URL(address, window.location.href).origin);
      } catch {
        // Not an address the browser understands: the engine refuses it with its reason.
      }
      for (const origin of config.dataOrigins) args.push('--allow-origin', origin);
    }
    const [wasmBytes] = await Promise.all([fetchWasm('quakeview-engine.wasm'), loadScript('quakeview-engine.js')]);
    setProgress(0.95, 'Starting…');
    const module = {
      canvas,
      arguments: args,
      qvHooks: {
        ready() {
          loading.hidden = true;
          resolveReady();
          // From now on the URL follows the view, so it can be shared at any moment.
          setInterval(keepHash, 500);
        },
        fatal,
        benchDone(json) {
          api.benchResult = JSON.parse(json);
          resolveBench(api.benchResult);
        },
      },
      instantiateWasm(imports, successCallback) {
        WebAssembly.instantiate(wasmBytes, imports)
          .then((result) => successCallback(result.instance, result.module))
          .catch((e) => fatal('The QuakeView engine could not start: ' + e.message));
        return {};
      },
      print(text) { console.log(text); },
      printErr(text) { console.warn(text); },
      onAbort(what) { fatal('The QuakeView engine stopped unexpectedly: ' + what); },
    };
    engine = await window.createQuakeViewEngine(module);
    setInterval(updateAccessibility, 250);
  }

  start().catch((e) => fatal('QuakeView could not load: ' + e.message));
})();
