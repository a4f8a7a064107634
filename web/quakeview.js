// QuakeView page shell: loads the engine (quakeview-engine.js/.wasm) with a progress bar, shows
// fatal errors on the page, and defines the scriptable API `window.quakeview`.
//
// API (kept for the life of the product; later versions only add members):
//   ready      Promise: resolves after the first frame in which everything of the initial view has
//              loaded or failed (without WebGL2 the page opens the 2D city: startMap2d); rejects with
//              an Error carrying the on-page message when the engine cannot start.
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
//   showDistrict(name), shownDistrict()   fly to a district of consequences() and outline it
//   report()   a Promise of the situation report: one print-ready HTML document (the event, headline
//              numbers with 90 % intervals, impact level, map, HAZUS tables, facilities, casualties
//              at 2 AM / 2 PM / 5 PM, districts, limits and sources), the same as `quakeview-prep
//              report` writes; it resolves once the city's index and totals have loaded (rejects
//              after 120 s or without a city). saveReport() downloads it (the panel's "Report").
//   scenarios()  a Promise of the city's scenarios (scenarios.json beside its manifest), once the
//              list has loaded ([] for a city without one): [{index, name, manifest, current, state
//              ('not checked' | 'checking' | 'ready' | 'not ready' | 'broken'), eventType ('SCENARIO' |
//              'ACTUAL' | null until its manifest is read), earthquake, sameResultsAsOpen}]; current:
//              the manifest shown is this one's (by file name).
//   selectScenario(index)  shows scenario `index` in the same view (camera, time, filters and
//              selection kept); a Promise resolving with its entry once its view and totals have
//              loaded, rejecting with the reason when it is not ready or not listed. The URL's
//              data= follows the scenario shown.
//   map()      extension: the map under the city: {layer ('none': made without one | 'empty': its
//              input had no streets, water or open land | 'present'), cells, cellsDrawn, cellsLoaded,
//              cellsFailed, triangles (the map's, last frame), bytes, features: {class: count},
//              skipped: {reason: count}, labels: [{text, kind ('street' | 'water' | 'park' |
//              'neighbourhood' | 'settlement'), x, y (CSS px, its centre), width, height (its text before
//              turning), angleDeg, facility}] drawn
//              last frame}; null before the city's manifest.
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

  // The city's scenario catalogue as the engine knows it (qv_scenarios_json), or null.
  function scenarioInfo() {
    const text = callString('qv_scenarios_json');
    return text ? JSON.parse(text) : null;
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
    map() {
      const text = callString('qv_map_json');
      return text ? JSON.parse(text) : null;
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
    // Fly to a district of consequences().districts and outline it ('' clears); the one outlined.
    showDistrict(name) {
      if (!engine || typeof name !== 'string') return false;
      return engine.ccall('qv_show_district', 'number', ['string'], [name]) === 1;
    },
    shownDistrict() { return callString('qv_shown_district'); },
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
    // The city folder's scenarios (see the header): a Promise resolving once the engine knows
    // whether the city has a catalogue (its manifest loaded and scenarios.json answered).
    scenarios() {
      return new Promise((resolve, reject) => {
        const started = Date.now();
        const poll = () => {
          const info = engine ? scenarioInfo() : null;
          if (info && info.catalogue !== 'loading') { resolve(info.scenarios); return; }
          if (Date.now() - started > 120000) {
            reject(new Error('the scenario list waited 120 s for the city\'s manifest and scenarios.json'));
            return;
          }
          setTimeout(poll, 100);
        };
        ready.then(poll, (e) => reject(e));
      });
    },
    // Shows scenario `index` of the catalogue (see the header).
    selectScenario(index) {
      return new Promise((resolve, reject) => {
        if (!engine) { reject(new Error('the viewer has not started')); return; }
        if (typeof index !== 'number' || !Number.isInteger(index) || index < 1) {
          reject(new Error('selectScenario(index): a scenario\'s index is a whole number from 1'));
          return;
        }
        const answer = JSON.parse(engine.UTF8ToString(engine._qv_select_scenario(index)));
        if (!answer.serial) { reject(new Error(answer.problem)); return; }
        const started = Date.now();
        const poll = () => {
          const info = scenarioInfo();
          const change = info && info.switch;
          if (!change || change.serial !== answer.serial) {
            reject(new Error(`another scenario was selected before scenario ${index} had loaded`));
            return;
          }
          if (change.state === 'loaded') {
            keepHash();
            resolve(info.scenarios.find((s) => s.index === index) || null);
            return;
          }
          if (change.state === 'failed') { reject(new Error(change.problem)); return; }
          if (Date.now() - started > 120000) {
            reject(new Error(`scenario ${index} had not loaded after 120 s`));
            return;
          }
          setTimeout(poll, 100);
        };
        poll();
      });
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

  // WebGL2 first. Without it (no GPU and no software fallback, a blocked driver, WebGL turned off)
  // the page opens the 2D city instead (map2d below): the same data, numbers, search, lists,
  // exports and report, the buildings drawn from above on a 2D canvas.
  const probe = document.createElement('canvas');
  const gl = probe.getContext('webgl2');
  const map2dMode = !gl || params.get('view') === '2d';
  // The renderer's name: a software rasterizer (SwiftShader, WARP, llvmpipe) makes the engine start
  // in its weak-device preset. Chromium masks RENDERER ("WebKit WebGL") and names the real one
  // through WEBGL_debug_renderer_info; Firefox answers RENDERER directly (and deprecates the
  // extension, so it is asked only when needed).
  let renderer = '';
  if (gl) {
    renderer = String(gl.getParameter(gl.RENDERER) || '');
    if (/^WebKit WebGL$/i.test(renderer) || renderer === '') {
      const info = gl.getExtension('WEBGL_debug_renderer_info');
      if (info) renderer = String(gl.getParameter(info.UNMASKED_RENDERER_WEBGL) || renderer);
    }
    const lose = gl.getExtension('WEBGL_lose_context');
    if (lose) lose.loseContext();
  }

  // Engine arguments from the page URL (the city's address is checked against the data origin
  // policy in start(), before anything of it is fetched).
  const args = [];
  if (params.get('scene')) args.push('--scene', params.get('scene'));
  if (params.get('aa') === '0') args.push('--no-antialias');
  if (params.get('aa') === '1') args.push('--antialias');
  if (params.get('quality')) args.push('--quality', params.get('quality'));
  if (renderer && !map2dMode) args.push('--webgl-renderer', renderer);
  if (map2dMode) args.push('--map2d');
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
  // The page's query with ?data= naming the manifest shown: after a switch to another scenario
  // (selectScenario, the panel's Scenarios) a shared link opens that scenario. Unchanged while it
  // names the manifest shown.
  function viewSearch() {
    const shown = engine ? callString('qv_manifest_url') : '';
    const query = new URLSearchParams(window.location.search);
    if (!shown || shown === (query.get('data') || DEFAULT_DATA)) return window.location.search;
    query.set('data', shown);
    // Slashes and colons read better unescaped, and mean the same in a query's value.
    return '?' + query.toString().replace(/%2F/gi, '/').replace(/%3A/gi, ':');
  }
  function keepHash() {
    const h = viewHash();
    if (h === null) return;
    const search = viewSearch();
    if ('#' + h !== window.location.hash || search !== window.location.search) {
      history.replaceState(null, '', window.location.pathname + search + '#' + h);
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

  // The city shown without ?data=.
  const DEFAULT_DATA = 'data/default/tileset.json';

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
      const address = params.get('data') || DEFAULT_DATA;
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
    if (map2dMode) startMap2d(!gl);
  }

  // ---- The 2D city, where no WebGL2 context can be made (or with ?view=2d) ----
  // The engine runs as in 3D (tiles chosen, loaded and culled for the view, the clock, the
  // results, the panels' content) but draws nothing: each frame the page reads the footprints of
  // the buildings in view, in the colours of the current colour mode (qv_map2d, qv/scene/Map2d.h),
  // and fills them on a 2D canvas, one path per colour. The panels are HTML: the engine's text of
  // them (the accessible copy, #qv-panel, made visible) under controls for what needs a click:
  // colour mode, playback, search, filters, the list, exports, the report. Pan by dragging (mouse or
  // one finger), zoom by the wheel, two fingers or +/-, arrows pan, click or tap to inspect.
  const map2d = { fps: 0, frames: 0, shapes: 0, drawMs: 0, engineMs: 0 };
  api.map2d = () => (map2dMode ? { ...map2d } : null);  // extension: {fps, frames, shapes, drawMs, engineMs} or null
  function startMap2d(noWebGl) {
    const g = canvas.getContext('2d', { alpha: false });
    if (!g) {
      fatal('Neither WebGL2 nor a 2D canvas is available in this browser, so the city cannot be drawn.');
      return;
    }
    document.body.classList.add('qv-map2d');
    canvas.setAttribute('aria-roledescription', '2D city map');
    canvas.setAttribute('aria-label', 'QuakeView: the city from above, each building coloured by the earthquake. ' +
      'Drag or use the arrows to pan, the wheel or plus and minus to zoom, click a building to inspect it.');
    const panel = document.getElementById('qv-panel');
    panel.classList.remove('visually-hidden');
    panel.classList.add('qv-map2d-panel');

    const el = (tag, props = {}, children = []) => {
      const e = document.createElement(tag);
      for (const [k, v] of Object.entries(props)) {
        if (k === 'text') e.textContent = v; else if (k in e) e[k] = v; else e.setAttribute(k, v);
      }
      for (const c of children) e.appendChild(c);
      return e;
    };
    const controls = el('div', { id: 'qv-map2d-controls' });
    panel.insertBefore(controls, panel.firstChild);
    controls.appendChild(el('p', { id: 'qv-map2d-notice', role: 'note', text: noWebGl
      ? 'The 3D view is off: this browser gives the page no WebGL2 (no graphics acceleration and no software ' +
        'renderer), so the city is shown from above in 2D, with the same results, search, lists, exports and ' +
        'report. An administrator turns the 3D view on by enabling graphics acceleration (Chrome and Edge: ' +
        'Settings, System, "Use graphics acceleration when available"; Firefox: about:config, webgl.disabled ' +
        'false, and webgl.force-enabled true where the driver is blocked) or the software renderer (Chromium ' +
        'started with --enable-unsafe-swiftshader).'
      : 'The 2D city (this link asks for it with ?view=2d): the same results, search, lists, exports and report.' }));

    // Colour mode and playback.
    const modeNames = { drift: 'Drift now', peak: 'Peak drift', damage: 'Damage state', neutral: 'Neutral',
      'p-moderate': 'P(moderate or worse)', 'expected-damage': 'Expected damage', tag: 'Inspection tag' };
    const mode = el('select', { id: 'qv-map2d-mode', 'aria-label': 'Colour' },
      COLOR_MODES.map((m) => el('option', { value: m, text: modeNames[m] })));
    mode.addEventListener('change', () => api.setColorMode(mode.value));
    const play = el('button', { type: 'button', id: 'qv-map2d-play', text: 'Pause' });
    play.addEventListener('click', () => { if (api.playing()) api.pause(); else api.play(); });
    const time = el('input', { type: 'range', id: 'qv-map2d-time', min: '0', max: '1', step: '0.1', 'aria-label': 'Time' });
    time.addEventListener('input', () => { api.pause(); api.setTime(Number(time.value)); });
    const timeText = el('span', { id: 'qv-map2d-time-text' });
    controls.appendChild(el('div', { class: 'qv-row' }, [el('label', { text: 'Colour ' }, [mode])]));
    // The city's scenarios (scenarios.json), as the 3D panel's Scenarios section lists them: the
    // one shown selected, a choice showing another.
    const scenario = el('select', { id: 'qv-map2d-scenario', 'aria-label': 'Scenario' });
    const scenarioRow = el('div', { class: 'qv-row', id: 'qv-map2d-scenarios' }, [el('label', { text: 'Scenario ' }, [scenario])]);
    scenarioRow.hidden = true;
    controls.appendChild(scenarioRow);
    scenario.addEventListener('change', () => {
      const index = Number(scenario.value);
      if (!Number.isInteger(index) || index < 1) return;
      setText(statusBox, 'Opening scenario ' + index + '...');
      api.selectScenario(index).then((s) => setText(statusBox, 'Showing ' + (s ? s.name : 'scenario ' + index)),
        (e) => { scenarioKey = ''; setText(statusBox, 'Scenario: ' + e.message); });
    });
    let scenarioKey = '';
    const refreshScenarios = () => {
      const info = scenarioInfo();
      const list = info && info.catalogue === 'loaded' ? info.scenarios : [];
      scenarioRow.hidden = list.length === 0;
      const current = list.find((s) => s.current);
      const change = info && info.switch && ['checking', 'loading'].includes(info.switch.state) ? info.switch.index : 0;
      const key = JSON.stringify([list.map((s) => [s.index, s.name, s.state, s.eventType, s.current]), change]);
      if (key === scenarioKey) return;  // rebuilt only when something changed (an open list stays open)
      scenarioKey = key;
      const words = { 'not ready': 'not ready', broken: 'cannot be read', checking: 'checking...', 'not checked': '' };
      const options = list.map((s) => el('option', { value: String(s.index),
        text: s.name + (s.eventType ? ` (${s.eventType})` : words[s.state] ? ` (${words[s.state]})` : '') }));
      if (!current) {
        // The manifest shown is not listed by name (tileset.json): say so rather than pretend.
        const same = list.find((s) => s.sameResultsAsOpen);
        options.unshift(el('option', { value: '', disabled: true,
          text: same ? `${same.name} (as opened)` : 'the city as opened (not in the list)' }));
      }
      scenario.replaceChildren(...options);
      scenario.value = change ? String(change) : current ? String(current.index) : '';
    };
    // The colour key of the mode shown (the engine's palette; the 3D view's legend says the same).
    const palette = JSON.parse(engine.UTF8ToString(engine._qv_palette_json()));
    const keys = {
      drift: ['0 % drift now', '0.1 %', '0.5 %', '1 %', '2 % or more'],
      peak: ['0 % peak drift', '0.1 %', '0.5 %', '1 %', '2 % or more'],
      damage: ['none', 'slight', 'moderate', 'extensive', 'complete'],
      'p-moderate': ['P(moderate or worse) 0 %', '25 %', '50 %', '75 %', '100 %'],
      'expected-damage': ['expected state 0 none', '1 slight', '2 moderate', '3 extensive', '4 complete'],
    };
    const legend = el('div', { id: 'qv-map2d-legend', class: 'qv-row' });
    controls.appendChild(legend);
    let legendMode = null;
    const swatch = (color, text) => {
      const box = el('span', { class: 'qv-swatch' });
      box.style.background = color;  // CSSOM, not a style attribute: allowed by the page's policy
      return el('span', { class: 'qv-key' }, [box, document.createTextNode(text)]);
    };
    const refreshLegend = () => {
      const shown = api.shownColorMode();
      if (shown === legendMode) return;
      legendMode = shown;
      const items = shown === 'tag'
        ? ['green: inspected', 'yellow: restricted use', 'red: unsafe'].map((text, i) => swatch(palette.tags[i], text))
        : (keys[shown] || []).map((text, i) => swatch(palette.ramp[i], text));
      if (shown !== 'neutral') items.push(swatch(palette.noResult, 'no result'));
      if (shown !== mode.value) items.unshift(el('span', { text: 'The shaking is over; showing:' }));
      legend.replaceChildren(...items);
    };
    controls.appendChild(el('div', { class: 'qv-row' }, [play, time, timeText]));

    // Search.
    const search = el('input', { type: 'search', id: 'qv-map2d-search', placeholder: 'Search buildings (name, address, id)',
      'aria-label': 'Search buildings' });
    const results = el('ul', { id: 'qv-map2d-results', class: 'qv-list' });
    const selectAndShow = (id) => {
      api.select(id);
      api.flyToSelection();
    };
    const showResults = () => {
      const q = search.value.trim();
      const hits = q ? api.search(q, 8) : [];
      results.replaceChildren(...hits.map((h) => el('li', {}, [Object.assign(
        el('button', { type: 'button', text: `${h.label}${h.address && h.label !== h.address ? ', ' + h.address : ''} (${h.damageState || 'no result'})` }),
        { onclick: () => selectAndShow(h.id) })])));
    };
    search.addEventListener('input', showResults);
    search.addEventListener('keydown', (e) => {
      if (e.key !== 'Enter') return;
      const hits = api.search(search.value.trim(), 1);
      if (hits.length) selectAndShow(hits[0].id);
    });
    controls.appendChild(el('div', { class: 'qv-row' }, [search]));
    controls.appendChild(results);

    // Filters and the list.
    const states = ['none', 'slight', 'moderate', 'extensive', 'complete'];
    const minDamage = el('select', { id: 'qv-map2d-min-damage', 'aria-label': 'Damage at least' },
      [el('option', { value: '', text: 'any damage' }), ...states.slice(1).map((s) => el('option', { value: s, text: `${s} or worse` }))]);
    const critical = el('input', { type: 'checkbox', id: 'qv-map2d-critical' });
    const applyFilters = () => api.setFilters({ minDamage: minDamage.value || null, criticalOnly: critical.checked });
    minDamage.addEventListener('change', applyFilters);
    critical.addEventListener('change', applyFilters);
    controls.appendChild(el('div', { class: 'qv-row' }, [el('label', { text: 'Show ' }, [minDamage]),
      el('label', { text: ' critical facilities only ' }, [critical])]));
    const listTitle = el('p', { class: 'qv-list-title' });
    const list = el('ul', { id: 'qv-map2d-list', class: 'qv-list' });
    controls.appendChild(listTitle);
    controls.appendChild(list);

    // Exports and the report.
    const button = (id, text, action) => Object.assign(el('button', { type: 'button', id, text }), { onclick: action });
    controls.appendChild(el('div', { class: 'qv-row' }, [
      button('qv-map2d-csv', 'Export CSV', () => api.exportList('csv')),
      button('qv-map2d-geojson', 'Export GeoJSON', () => api.exportList('geojson')),
      button('qv-map2d-report', 'Report (HTML)', () => { api.saveReport().catch((e) => setText(statusBox, 'Report: ' + e.message)); }),
      button('qv-map2d-image', 'Save image (PNG)', () => api.saveImage()),
    ]));

    let listKey = '';
    const refreshPanel = () => {
      refreshLegend();
      refreshScenarios();
      const m = api.colorMode();
      if (m && mode.value !== m) mode.value = m;
      play.textContent = api.playing() ? 'Pause' : 'Play';
      time.max = String(Math.max(api.duration(), 0.1));
      if (document.activeElement !== time) time.value = String(api.time());
      timeText.textContent = ` ${api.time().toFixed(1)} s of ${api.duration().toFixed(1)} s`;
      if (!api.searchReady()) {
        // Also after a switch to another scenario: the last one's list is not this one's.
        listTitle.textContent = 'The city-wide list loads with the search index...';
        if (listKey !== '') { list.replaceChildren(); listKey = ''; }
        return;
      }
      const f = api.filteredList(10);
      const key = JSON.stringify([f.total, f.buildings.map((b) => b.id), api.selection()]);
      if (key === listKey) return;
      listKey = key;
      listTitle.textContent = `${f.total.toLocaleString('en-US')} buildings pass the filters, most likely damaged first:`;
      // The probability the list sorts by (as the panel's list): the damage filter's state, else slight.
      const by = minDamage.value && minDamage.value !== 'none' ? minDamage.value : 'slight';
      list.replaceChildren(...f.buildings.map((b) => el('li', {}, [Object.assign(el('button', { type: 'button',
        text: `${b.label || b.name || b.id}: ${b.damageState || 'no result'}${b.probabilityAtLeast ? `, P(${by} or worse) ${Math.round(100 * b.probabilityAtLeast[by])} %` : ''}` }),
      { onclick: () => selectAndShow(b.id) })])));
    };
    setInterval(refreshPanel, 300);

    // Drawing: buildings under two pixels are written as pixels of one image (a hundred thousand
    // dots cost a few milliseconds that way, against tens as paths); larger footprints are filled,
    // one path per colour, over it.
    const background = [0xdf, 0xe3, 0xe6];
    let image = null;
    let pixels = null;
    let frameTimes = [];
    function draw(now) {
      requestAnimationFrame(draw);
      if (!engine) return;
      const t0 = performance.now();
      const ptr = engine._qv_map2d();
      const n = engine._qv_map2d_floats();
      const t1 = performance.now();
      const f = engine.HEAPF32.subarray(ptr >> 2, (ptr >> 2) + n);
      const width = canvas.width;
      const height = canvas.height;
      if (width === 0 || height === 0) return;
      const ratio = canvas.clientWidth > 0 ? width / canvas.clientWidth : 1;
      if (!image || image.width !== width || image.height !== height) {
        image = g.createImageData(width, height);
        pixels = new Uint32Array(image.data.buffer);
      }
      // Little-endian RGBA as one 32-bit word: 0xAABBGGRR.
      pixels.fill((255 << 24) | (background[2] << 16) | (background[1] << 8) | background[0]);
      const paths = new Map();
      let shapes = 0;
      const dot = Math.max(1, Math.round(2 * ratio));
      for (let i = 0; i + 1 < n;) {
        const color = f[i];
        const count = f[i + 1];
        i += 2;
        ++shapes;
        if (count === 1) {
          const x0 = Math.round(f[i] * ratio - dot / 2);
          const y0 = Math.round(f[i + 1] * ratio - dot / 2);
          i += 2;
          const rgb = Math.round(color);
          const word = (255 << 24) | ((rgb & 0xff) << 16) | (rgb & 0xff00) | ((rgb >> 16) & 0xff);
          for (let y = Math.max(y0, 0); y < Math.min(y0 + dot, height); ++y) {
            const row = y * width;
            for (let x = Math.max(x0, 0); x < Math.min(x0 + dot, width); ++x) pixels[row + x] = word;
          }
          continue;
        }
        let p = paths.get(color);
        if (!p) { p = new Path2D(); paths.set(color, p); }
        p.moveTo(f[i], f[i + 1]);
        for (let k = 1; k < count; ++k) p.lineTo(f[i + 2 * k], f[i + 2 * k + 1]);
        p.closePath();
        i += 2 * count;
      }
      g.putImageData(image, 0, 0);
      g.setTransform(ratio, 0, 0, ratio, 0, 0);
      for (const [color, p] of paths) {
        g.fillStyle = '#' + Math.round(color).toString(16).padStart(6, '0');
        g.fill(p);
      }
      g.setTransform(1, 0, 0, 1, 0, 0);
      // Fitted twice: the first view may cut the city at the screen's edges (culled there), the
      // second sees all of it.
      if (fitted < 2 && shapes > 0 && readyResolved && now >= fitAfter) {
        fitCity(f, n);
        fitAfter = now + 800;
      }
      map2d.shapes = shapes;
      map2d.engineMs = t1 - t0;
      map2d.drawMs = performance.now() - t0;
      frameTimes.push(now);
      frameTimes = frameTimes.filter((x) => now - x < 1000);
      map2d.fps = frameTimes.length;
      ++map2d.frames;
    }
    requestAnimationFrame(draw);

    // Once the city is there: it fills the map beside the panel (the 3D view's framing is for an
    // oblique view; from above the same distance leaves it small).
    let fitted = 0;
    let fitAfter = 0;
    let readyResolved = false;
    ready.then(() => { readyResolved = true; }, () => {});
    function fitCity(f, n) {
      ++fitted;
      let minX = Infinity, minY = Infinity, maxX = -Infinity, maxY = -Infinity;
      for (let i = 0; i + 1 < n;) {
        const count = f[i + 1];
        i += 2;
        for (let k = 0; k < count; ++k) {
          minX = Math.min(minX, f[i + 2 * k]); maxX = Math.max(maxX, f[i + 2 * k]);
          minY = Math.min(minY, f[i + 2 * k + 1]); maxY = Math.max(maxY, f[i + 2 * k + 1]);
        }
        i += 2 * count;
      }
      if (!(maxX > minX && maxY > minY)) return;
      const r = canvas.getBoundingClientRect();
      const panelRight = Math.min(panel.getBoundingClientRect().right + 10, r.width * 0.5);
      const areaW = r.width - panelRight - 40;
      const areaH = r.height - 60;
      const factor = Math.max((maxX - minX) / areaW, (maxY - minY) / areaH);
      // Centre the city's box in the area right of the panel, then zoom by `factor` about it.
      const m = metresPerCss();
      const c = api.getCamera();
      const boxCx = (minX + maxX) / 2, boxCy = (minY + maxY) / 2;
      const groundX = c.x + (boxCx - r.width / 2) * m, groundY = c.y - (boxCy - r.height / 2) * m;
      const distance = Math.min(Math.max(c.distance * factor, 20), 200000);
      const areaCx = panelRight + 20 + areaW / 2;
      const mNew = m * distance / c.distance;
      api.setCamera({ distance, x: groundX - (areaCx - r.width / 2) * mNew, y: groundY });
    }

    // Pan and zoom on the ground seen from above.
    const metresPerCss = () => {
      const c = api.getCamera();
      const a = api.worldToScreen(c.x, c.y, 0);
      const b = api.worldToScreen(c.x + 100, c.y, 0);
      return a && b && b[0] !== a[0] ? 100 / (b[0] - a[0]) : 1;
    };
    const panBy = (dxCss, dyCss) => {
      const c = api.getCamera();
      const m = metresPerCss();
      api.setCamera({ x: c.x - dxCss * m, y: c.y + dyCss * m });
    };
    const zoomAt = (factor, xCss, yCss) => {
      const c = api.getCamera();
      const m = metresPerCss();
      const r = canvas.getBoundingClientRect();
      // The ground under the pointer stays under it.
      const ox = (xCss - r.width / 2) * m;
      const oy = -(yCss - r.height / 2) * m;
      const distance = Math.min(Math.max(c.distance * factor, 20), 200000);
      const k = 1 - distance / c.distance;
      api.setCamera({ distance, x: c.x + ox * k, y: c.y + oy * k });
    };
    const pointers = new Map();
    let press = null;  // {x, y, moved}
    let pinch = null;  // {distance}
    canvas.addEventListener('pointerdown', (e) => {
      canvas.setPointerCapture(e.pointerId);
      pointers.set(e.pointerId, { x: e.offsetX, y: e.offsetY });
      press = pointers.size === 1 ? { x: e.offsetX, y: e.offsetY, moved: false } : null;
      if (pointers.size === 2) {
        const [a, b] = [...pointers.values()];
        pinch = { distance: Math.hypot(a.x - b.x, a.y - b.y) };
      }
    });
    canvas.addEventListener('pointermove', (e) => {
      const last = pointers.get(e.pointerId);
      if (!last) return;
      const now = { x: e.offsetX, y: e.offsetY };
      pointers.set(e.pointerId, now);
      if (pointers.size === 1) {
        if (press && Math.hypot(now.x - press.x, now.y - press.y) > 4) press.moved = true;
        if (!press || press.moved) panBy(now.x - last.x, now.y - last.y);
      } else if (pointers.size === 2 && pinch) {
        const [a, b] = [...pointers.values()];
        const d = Math.hypot(a.x - b.x, a.y - b.y);
        if (d > 0 && pinch.distance > 0) zoomAt(pinch.distance / d, (a.x + b.x) / 2, (a.y + b.y) / 2);
        pinch.distance = d;
      }
    });
    const release = (e) => {
      pointers.delete(e.pointerId);
      if (pointers.size < 2) pinch = null;
      if (e.type === 'pointerup' && press && !press.moved && pointers.size === 0) {
        const hit = api.pick(e.offsetX, e.offsetY);
        api.select(hit ? hit.id : '');
      }
      if (pointers.size === 0) press = null;
    };
    canvas.addEventListener('pointerup', release);
    canvas.addEventListener('pointercancel', release);
    canvas.addEventListener('wheel', (e) => {
      e.preventDefault();
      zoomAt(Math.exp(e.deltaY * (e.deltaMode === 1 ? 0.05 : 0.0015)), e.offsetX, e.offsetY);
    }, { passive: false });
    canvas.addEventListener('keydown', (e) => {
      const step = 80;
      const r = canvas.getBoundingClientRect();
      const keys = { ArrowLeft: () => panBy(step, 0), ArrowRight: () => panBy(-step, 0), ArrowUp: () => panBy(0, step),
        ArrowDown: () => panBy(0, -step), '+': () => zoomAt(1 / 1.4, r.width / 2, r.height / 2),
        '=': () => zoomAt(1 / 1.4, r.width / 2, r.height / 2), '-': () => zoomAt(1.4, r.width / 2, r.height / 2),
        ' ': () => (api.playing() ? api.pause() : api.play()) };
      const action = keys[e.key];
      if (!action) return;
      e.preventDefault();
      action();
    });
  }

  start().catch((e) => fatal('QuakeView could not load: ' + e.message));
})();
