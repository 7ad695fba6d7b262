// The studio drawing's zoom and pan in the browser: the front end of img2logo.studio.zoom_pan.ZoomPan.
//
// The wheel and a pan's drag never wait for the kernel. At each one the frame on screen is the
// drawing the canvas already holds, scaled and moved to the new view at once; the operation goes
// to Python, which holds the view (its truth), applies it with its own zoom_at / pan_by and
// redraws the layers exactly. Operations made while a message is unanswered wait and go together
// with the next one (Python applies them in order: quick notches end where slow ones do). Every
// view Python draws is announced by a message ("view") sent before its drawing, and that drawing
// ends on an undisplayed marker canvas: the n-th marker frame is the n-th view announced, so the
// frame on screen is always the drawing of the view it holds, moved to the view wanted.
//
// ipycanvas gives no public hook for a drawing's arrival; this module uses its front end's
// MultiCanvasModel as ipycanvas's own drawImage(multi_canvas) does: `canvas` (the layers
// composited), `views` (the canvas elements shown) and its layers' "new-frame" event.

/** The view [scale, x, y] (canvas px per image px, the image corner's canvas position), null: fitted. */
function concrete(geometry, view) {
  return view ?? geometry.fit;
}

/** Zoom by factor about canvas point (x, y): StudioDrawing.zoom_at's arithmetic. */
function zoomAt(geometry, view, x, y, factor) {
  const [k0, x0, y0] = concrete(geometry, view);
  const fit = geometry.fit[0];
  const k = Math.min(Math.max(k0 * factor, fit), fit * geometry.max_zoom);
  const ix = (x - x0) / k0;
  const iy = (y - y0) / k0;
  return k <= fit * (1 + 1e-9) ? null : [k, x - ix * k, y - iy * k];
}

/** Move a zoomed view by (dx, dy) canvas px: StudioDrawing.pan_by's arithmetic. */
function panBy(geometry, view, dx, dy) {
  if (view === null) {
    return null;
  }
  const [k, x, y] = view;
  const [w, h] = [geometry.size[0] * k, geometry.size[1] * k];
  const keep = geometry.keep;
  const side = geometry.side;
  return [k, Math.min(Math.max(x + dx, keep - w), side - keep), Math.min(Math.max(y + dy, keep - h), side - keep)];
}

function apply(geometry, view, ops) {
  for (const [kind, a, b, c] of ops) {
    view = kind === "zoom" ? zoomAt(geometry, view, a, b, c) : panBy(geometry, view, a, b);
  }
  return view;
}

async function modelOf(model, reference) {
  return model.widget_manager.get_model(String(reference).replace(/^IPY_MODEL_/, ""));
}

export default {
  async render({ model }) {
    const drawing = await modelOf(model, model.get("canvas"));
    const marker = await modelOf(model, model.get("marker"));
    const layers = drawing.get("_canvases");
    let geometry = model.get("geometry");
    let answered = geometry.view; // Python's view after the last message it answered (null: fitted)
    let drawn = concrete(geometry, answered); // the view of the drawing the layers hold now, [scale, x, y]
    let sent = []; // the operations of the messages sent and not yet answered, one list each
    let waiting = []; // operations not sent yet (a message is unanswered)
    const announced = []; // views announced whose drawing has not arrived
    const elements = new Set();
    const wanted = () => apply(geometry, answered, [...sent.flat(), ...waiting]);

    const exact = () => {
      const view = concrete(geometry, wanted());
      return drawn.every((v, i) => v === view[i]);
    };
    /** The frame on screen: the layers' drawing (of view `drawn`) moved to the view wanted.
     *
     * The canvas element's data-view says which: "exact" (the layers' own drawing of the view
     * wanted) or "moved" (until the exact drawing comes).
     */
    function present() {
      const [kd, xd, yd] = drawn;
      const [kw, xw, yw] = concrete(geometry, wanted());
      const s = kw / kd;
      const shown = exact() ? "exact" : "moved";
      for (const el of elements) {
        el.dataset.view = shown;
        const ctx = el.getContext("2d");
        ctx.save();
        ctx.setTransform(1, 0, 0, 1, 0, 0);
        ctx.fillStyle = geometry.frame;
        ctx.fillRect(0, 0, el.width, el.height);
        ctx.setTransform(s, 0, 0, s, xw - xd * s, yw - yd * s);
        ctx.drawImage(drawing.canvas, 0, 0);
        ctx.restore();
      }
    }
    let scheduled = false;
    /** present() once ipycanvas has put a new drawing on screen (its views update a microtask later). */
    function presentSoon() {
      if (!scheduled) {
        scheduled = true;
        requestAnimationFrame(() => {
          scheduled = false;
          present();
        });
      }
    }
    function send() {
      if (waiting.length) {
        model.send({ ops: waiting });
        sent.push(waiting);
        waiting = [];
      }
    }
    function operate(op) {
      waiting.push(op);
      if (!sent.length) {
        send();
      }
      present();
    }

    function onMessage(msg) {
      if (!msg || msg.view === undefined) {
        return;
      }
      if (msg.answer) {
        sent.shift();
      }
      geometry = msg.geometry;
      answered = msg.view;
      announced.push(concrete(msg.geometry, msg.view));
      if (!sent.length) {
        send(); // what came meanwhile, together
      }
    }
    function onMarkerFrame() {
      drawn = announced.length ? announced.shift() : concrete(geometry, answered);
      presentSoon();
    }
    function onLayerFrame() {
      if (!exact()) {
        presentSoon(); // ipycanvas drew the layers as they are: moved to the view wanted again
      }
    }
    model.on("msg:custom", onMessage);
    marker.on("new-frame", onMarkerFrame);
    for (const layer of layers) {
      layer.on("new-frame", onLayerFrame);
    }

    // The events of each canvas element showing the drawing; ours run before ipycanvas's (capture).
    let space = false;
    let drag = null; // the last pointer position of a pan, canvas px
    const point = (el, e) => {
      const r = el.getBoundingClientRect();
      return [((e.clientX - r.left) * el.width) / r.width, ((e.clientY - r.top) * el.height) / r.height];
    };
    const removers = [];
    function listen(target, type, handler, options) {
      target.addEventListener(type, handler, options);
      removers.push(() => target.removeEventListener(type, handler, options));
    }
    function attach(el) {
      if (elements.has(el)) {
        return;
      }
      elements.add(el);
      el.dataset.view = exact() ? "exact" : "moved";
      const capture = { capture: true, passive: false };
      listen(el, "wheel", (e) => {
        e.preventDefault();
        e.stopImmediatePropagation();
        if (e.deltaY) {
          const [x, y] = point(el, e);
          operate(["zoom", x, y, Math.pow(geometry.step, -Math.sign(e.deltaY))]);
        }
      }, capture);
      listen(el, "keydown", (e) => {
        if (e.key === " ") {
          e.preventDefault();
          e.stopImmediatePropagation();
          space = true;
        } else {
          send(); // a key acts on the view on screen
        }
      }, capture);
      listen(el, "keyup", (e) => {
        if (e.key === " ") {
          space = false;
        }
      }, capture);
      listen(el, "blur", () => {
        space = false;
      }, capture);
      listen(el, "mousedown", (e) => {
        if (e.button !== 0 || !(space || model.get("tool_index") === model.get("pan_tool"))) {
          send(); // a click or a drag of the tool acts on the view on screen
          return;
        }
        e.preventDefault();
        e.stopImmediatePropagation();
        el.focus();
        drag = [el, point(el, e)];
      }, capture);
      listen(el, "mousemove", (e) => {
        if (e.buttons) {
          send();
        }
      }, capture);
      listen(el, "mouseup", () => send(), capture);
    }
    // A pan's moves and release, wherever the mouse goes, are the pan's only (not the tool's).
    listen(window, "mousemove", (e) => {
      if (drag) {
        e.stopImmediatePropagation();
        const [el, [x0, y0]] = drag;
        const [x, y] = point(el, e);
        drag = [el, [x, y]];
        operate(["pan", x - x0, y - y0]);
      }
    }, { capture: true });
    for (const type of ["mouseup", "mouseout", "mouseover"]) {
      listen(window, type, (e) => {
        if (drag) {
          e.stopImmediatePropagation();
          if (type === "mouseup") {
            drag = null;
            send();
          }
        }
      }, { capture: true });
    }
    for (const view of Object.values(drawing.views ?? {})) {
      attach((await view).el);
    }
    return () => {
      removers.forEach((remove) => remove());
      model.off("msg:custom", onMessage);
      marker.off("new-frame", onMarkerFrame);
      layers.forEach((layer) => layer.off("new-frame", onLayerFrame));
    };
  },
};
