// One sketching canvas of the editor: the side view (profiles: u = r, v = y) or the top view
// (sections: u = x, v = -z, so polar angles turn counter-clockwise), both in template units
// with v up. Under the curves lies an optional reference photo, scaled by a line of known
// length, moved and turned by dragging (the paper's §4: sketching over a photo of the real
// object). Tools: draw (a stroke becomes a curve), edit (drag a point), scale, move photo,
// turn photo, eyedropper.
// The view only draws and reports; the editor decides what a stroke or a drag changes.

const HIT_PIXELS = 9;

export class SketchView {
  /// @param canvas   the <canvas>
  /// @param handlers {stroke(points), movePoint(curve, index, point, done), scale(worldLength),
  ///                  pick(hex)}: called with world (template-unit) coordinates
  constructor(canvas, handlers) {
    this.canvas = canvas;
    this.ctx = canvas.getContext('2d');
    this.handlers = handlers;
    this.tool = 'draw';
    this.curves = [];      // {points, fitted, closed, mirror, colour, selected, error}
    this.guides = [];      // through the origin: {angle (radians), dashed, ray}
    this.photo = null;     // {image, pixels (canvas with its bytes), unitsPerPixel,
                           //  centre: [u, v], angle (radians, counter-clockwise)}
    this.frame(-50, 50, -10, 90);
    this.gesture = null;
    canvas.addEventListener('pointerdown', (e) => this.down(e));
    canvas.addEventListener('pointermove', (e) => this.move(e));
    canvas.addEventListener('pointerup', (e) => this.up(e));
    canvas.addEventListener('wheel', (e) => this.zoom(e), { passive: false });
    new ResizeObserver(() => this.draw()).observe(canvas);
  }

  /// Shows the world rectangle [u0, u1] x [v0, v1] whole, centred.
  frame(u0, u1, v0, v1) {
    this.view = { u0, u1, v0, v1 };
    this.draw();
  }

  scale() {
    const { u0, u1, v0, v1 } = this.view;
    const w = this.canvas.clientWidth || 400, h = this.canvas.clientHeight || 400;
    return Math.min(w / (u1 - u0), h / (v1 - v0));
  }

  /// World point of a canvas point (CSS pixels), and back.
  toWorld(x, y) {
    const s = this.scale(), { u0, u1, v0, v1 } = this.view;
    const w = this.canvas.clientWidth, h = this.canvas.clientHeight;
    return [(u0 + u1) / 2 + (x - w / 2) / s, (v0 + v1) / 2 - (y - h / 2) / s];
  }

  toCanvas([u, v]) {
    const s = this.scale(), { u0, u1, v0, v1 } = this.view;
    const w = this.canvas.clientWidth, h = this.canvas.clientHeight;
    return [w / 2 + (u - (u0 + u1) / 2) * s, h / 2 - (v - (v0 + v1) / 2) * s];
  }

  /// Lays `image` under the curves, its height filling most of the view.
  setPhoto(image) {
    const pixels = document.createElement('canvas');
    pixels.width = image.naturalWidth;
    pixels.height = image.naturalHeight;
    pixels.getContext('2d').drawImage(image, 0, 0);
    const { u0, u1, v0, v1 } = this.view;
    this.photo = { image, pixels, unitsPerPixel: 0.9 * (v1 - v0) / image.naturalHeight,
                   centre: [(u0 + u1) / 2, (v0 + v1) / 2], angle: 0 };
    this.draw();
  }

  /// Rescales the photo so that the world segment a-b (drawn over it) is `length` units long,
  /// keeping the segment's middle in place.
  scalePhoto(a, b, length) {
    const p = this.photo;
    const factor = length / Math.hypot(b[0] - a[0], b[1] - a[1]);
    const mid = [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2];
    p.unitsPerPixel *= factor;
    p.centre = [mid[0] + (p.centre[0] - mid[0]) * factor, mid[1] + (p.centre[1] - mid[1]) * factor];
    this.draw();
  }

  /// "#rrggbb" of the photo under world point `w`, or null off the photo.
  photoColour(w) {
    const p = this.photo;
    if (!p) return null;
    const du = w[0] - p.centre[0], dv = w[1] - p.centre[1];
    const c = Math.cos(p.angle), s = Math.sin(p.angle);  // turn back by the photo's angle
    const x = Math.floor((c * du + s * dv) / p.unitsPerPixel + p.pixels.width / 2);
    const y = Math.floor(-(-s * du + c * dv) / p.unitsPerPixel + p.pixels.height / 2);
    if (x < 0 || y < 0 || x >= p.pixels.width || y >= p.pixels.height) return null;
    const d = p.pixels.getContext('2d').getImageData(x, y, 1, 1).data;
    return '#' + [d[0], d[1], d[2]].map((c) => c.toString(16).padStart(2, '0')).join('');
  }

  point(e) {
    const r = this.canvas.getBoundingClientRect();
    return [e.clientX - r.left, e.clientY - r.top];
  }

  /// The selected curve's point within HIT_PIXELS of canvas point `c`: [curve, index] or null.
  hit(c) {
    let best = null, bestD = HIT_PIXELS;
    this.curves.forEach((curve, ci) => {
      if (!curve.selected) return;
      curve.points.forEach((p, i) => {
        const q = this.toCanvas(p);
        const d = Math.hypot(q[0] - c[0], q[1] - c[1]);
        if (d < bestD) { bestD = d; best = [ci, i]; }
      });
    });
    return best;
  }

  down(e) {
    const c = this.point(e), w = this.toWorld(...c);
    this.canvas.setPointerCapture(e.pointerId);
    if (this.tool === 'eyedropper') {
      const hex = this.photoColour(w);
      if (hex) this.handlers.pick(hex);
      return;
    }
    if (this.tool === 'edit') {
      const h = this.hit(c);
      this.gesture = h ? { kind: 'drag', curve: h[0], index: h[1] } : null;
      return;
    }
    if (['scale', 'move-photo', 'turn-photo'].includes(this.tool) && !this.photo) return;
    this.gesture = { kind: this.tool, stroke: [w], start: w };
  }

  move(e) {
    const g = this.gesture;
    if (!g) return;
    const w = this.toWorld(...this.point(e));
    if (g.kind === 'drag') {
      this.curves[g.curve].points[g.index] = w;
      this.handlers.movePoint(g.curve, g.index, w, false);
    } else if (g.kind === 'move-photo') {
      const last = g.stroke[g.stroke.length - 1];
      this.photo.centre = [this.photo.centre[0] + w[0] - last[0], this.photo.centre[1] + w[1] - last[1]];
      g.stroke.push(w);
    } else if (g.kind === 'turn-photo') {
      const last = g.stroke[g.stroke.length - 1], c = this.photo.centre;
      this.photo.angle += Math.atan2(w[1] - c[1], w[0] - c[0]) -
                          Math.atan2(last[1] - c[1], last[0] - c[0]);
      g.stroke.push(w);
    } else {
      g.stroke.push(w);
    }
    this.draw();
  }

  up(e) {
    const g = this.gesture;
    this.gesture = null;
    if (!g) return;
    const w = this.toWorld(...this.point(e));
    if (g.kind === 'drag') {
      this.handlers.movePoint(g.curve, g.index, w, true);
    } else if (g.kind === 'draw' && g.stroke.length > 2) {
      this.handlers.stroke(g.stroke);
    } else if (g.kind === 'scale') {
      const length = Math.hypot(w[0] - g.start[0], w[1] - g.start[1]);
      if (length > 0) {
        const known = this.handlers.scale(length);
        if (known > 0) this.scalePhoto(g.start, w, known);
      }
    }
    this.draw();
  }

  zoom(e) {
    e.preventDefault();
    const c = this.point(e), w = this.toWorld(...c);
    const f = Math.exp(Math.sign(e.deltaY) * 0.1);
    const { u0, u1, v0, v1 } = this.view;
    this.frame(w[0] + (u0 - w[0]) * f, w[0] + (u1 - w[0]) * f, w[1] + (v0 - w[1]) * f,
               w[1] + (v1 - w[1]) * f);
  }

  path(points, closed, mirror = false) {
    const ctx = this.ctx;
    ctx.beginPath();
    points.forEach((p, i) => {
      const q = this.toCanvas(mirror ? [-p[0], p[1]] : p);
      if (i === 0) ctx.moveTo(q[0], q[1]); else ctx.lineTo(q[0], q[1]);
    });
    if (closed) ctx.closePath();
  }

  draw() {
    const canvas = this.canvas, ctx = this.ctx;
    const dpr = window.devicePixelRatio || 1;
    const w = canvas.clientWidth, h = canvas.clientHeight;
    if (canvas.width !== Math.round(w * dpr) || canvas.height !== Math.round(h * dpr)) {
      canvas.width = Math.round(w * dpr);
      canvas.height = Math.round(h * dpr);
    }
    ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
    ctx.fillStyle = '#fbfbf8';
    ctx.fillRect(0, 0, w, h);
    const p = this.photo;
    if (p) {
      const s = this.scale();
      const [cx, cy] = this.toCanvas(p.centre);
      const pw = p.pixels.width * p.unitsPerPixel * s, ph = p.pixels.height * p.unitsPerPixel * s;
      ctx.save();
      ctx.globalAlpha = 0.75;
      ctx.translate(cx, cy);
      ctx.rotate(-p.angle);  // the canvas's y points down
      ctx.drawImage(p.image, -pw / 2, -ph / 2, pw, ph);
      ctx.restore();
    }
    const r = Math.hypot(w, h) / this.scale();
    for (const g of this.guides) {
      ctx.strokeStyle = '#99a';
      ctx.setLineDash(g.dashed ? [4, 4] : []);
      ctx.lineWidth = 1;
      const from = g.ray ? 0 : -r;  // a ray starts at the origin, a line crosses it
      this.path([[from * Math.cos(g.angle), from * Math.sin(g.angle)],
                 [r * Math.cos(g.angle), r * Math.sin(g.angle)]], false);
      ctx.stroke();
    }
    ctx.setLineDash([]);
    for (const c of this.curves) {
      ctx.strokeStyle = c.error ? '#d00' : c.colour;
      ctx.globalAlpha = c.selected || c.error ? 1 : 0.55;
      ctx.lineWidth = c.selected ? 2.5 : 1.5;
      const line = c.fitted && c.fitted.length ? c.fitted : c.points;
      this.path(line, c.closed);
      ctx.stroke();
      if (c.mirror) {
        ctx.globalAlpha = 0.25;
        this.path(line, c.closed, true);
        ctx.stroke();
      }
      ctx.globalAlpha = 1;
      if (c.selected) {
        ctx.fillStyle = c.error ? '#d00' : '#fff';
        ctx.strokeStyle = '#333';
        ctx.lineWidth = 1;
        for (const q of c.points.map((x) => this.toCanvas(x))) {
          ctx.beginPath();
          ctx.arc(q[0], q[1], 4, 0, 2 * Math.PI);
          ctx.fill();
          ctx.stroke();
        }
      }
    }
    const g = this.gesture;
    if (g && (g.kind === 'draw' || g.kind === 'scale')) {
      ctx.strokeStyle = g.kind === 'scale' ? '#07c' : '#333';
      ctx.lineWidth = 1.5;
      this.path(g.kind === 'scale' ? [g.start, g.stroke[g.stroke.length - 1]] : g.stroke, false);
      ctx.stroke();
    }
  }
}
