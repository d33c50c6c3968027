// The SF/MF classes of annex C (ISO/IEC 14772-1 C.6) written in ECMAScript 5: compiled
// once into each Script heap before the Script's own code. The host (script_values.cpp)
// builds and reads these objects directly: SFVec2f {x,y}, SFVec3f {x,y,z}, SFColor
// {r,g,b}, SFRotation {x,y,z,angle}, SFImage {x,y,comp,array}; the MF classes are real
// Arrays whose prototype is MFxxx.prototype (so `length` and `v[i] = y` work natively).
#include "script_ecmascript_internal.hpp"

namespace gs::runtime::es {

const char* const kPrelude = R"JS((function (G) {
'use strict';
function n(v) { v = +v; return v === v ? v : 0; }
function fmt(v) { return String(v); }
function defineIndexes(proto, names) {
  names.forEach(function (name, i) {
    Object.defineProperty(proto, String(i), {
      get: function () { return this[name]; },
      set: function (v) { this[name] = +v; },
      enumerable: false, configurable: false
    });
  });
}
function method(proto, name, fn) {
  Object.defineProperty(proto, name, { value: fn, writable: true, enumerable: false, configurable: true });
}

// ---- SFVec2f ----
function SFVec2f(x, y) {
  if (!(this instanceof SFVec2f)) return new SFVec2f(x, y);
  this.x = n(x); this.y = n(y);
}
defineIndexes(SFVec2f.prototype, ['x', 'y']);
method(SFVec2f.prototype, 'add', function (v) { return new SFVec2f(this.x + v.x, this.y + v.y); });
method(SFVec2f.prototype, 'subtract', function (v) { return new SFVec2f(this.x - v.x, this.y - v.y); });
method(SFVec2f.prototype, 'multiply', function (s) { return new SFVec2f(this.x * s, this.y * s); });
method(SFVec2f.prototype, 'divide', function (s) { return new SFVec2f(this.x / s, this.y / s); });
method(SFVec2f.prototype, 'dot', function (v) { return this.x * v.x + this.y * v.y; });
method(SFVec2f.prototype, 'length', function () { return Math.sqrt(this.x * this.x + this.y * this.y); });
method(SFVec2f.prototype, 'negate', function () { return new SFVec2f(-this.x, -this.y); });
method(SFVec2f.prototype, 'normalize', function () {
  var l = this.length();
  return l > 0 ? new SFVec2f(this.x / l, this.y / l) : new SFVec2f(0, 0);
});
method(SFVec2f.prototype, 'toString', function () { return fmt(this.x) + ' ' + fmt(this.y); });

// ---- SFVec3f ----
function SFVec3f(x, y, z) {
  if (!(this instanceof SFVec3f)) return new SFVec3f(x, y, z);
  this.x = n(x); this.y = n(y); this.z = n(z);
}
defineIndexes(SFVec3f.prototype, ['x', 'y', 'z']);
method(SFVec3f.prototype, 'add', function (v) { return new SFVec3f(this.x + v.x, this.y + v.y, this.z + v.z); });
method(SFVec3f.prototype, 'subtract', function (v) { return new SFVec3f(this.x - v.x, this.y - v.y, this.z - v.z); });
method(SFVec3f.prototype, 'multiply', function (s) { return new SFVec3f(this.x * s, this.y * s, this.z * s); });
method(SFVec3f.prototype, 'divide', function (s) { return new SFVec3f(this.x / s, this.y / s, this.z / s); });
method(SFVec3f.prototype, 'dot', function (v) { return this.x * v.x + this.y * v.y + this.z * v.z; });
method(SFVec3f.prototype, 'cross', function (v) {
  return new SFVec3f(this.y * v.z - this.z * v.y, this.z * v.x - this.x * v.z, this.x * v.y - this.y * v.x);
});
method(SFVec3f.prototype, 'length', function () { return Math.sqrt(this.dot(this)); });
method(SFVec3f.prototype, 'negate', function () { return new SFVec3f(-this.x, -this.y, -this.z); });
method(SFVec3f.prototype, 'normalize', function () {
  var l = this.length();
  return l > 0 ? new SFVec3f(this.x / l, this.y / l, this.z / l) : new SFVec3f(0, 0, 0);
});
method(SFVec3f.prototype, 'toString', function () { return fmt(this.x) + ' ' + fmt(this.y) + ' ' + fmt(this.z); });

// ---- SFColor (HSV: h in degrees [0, 360), s and v in [0, 1]) ----
function SFColor(r, g, b) {
  if (!(this instanceof SFColor)) return new SFColor(r, g, b);
  this.r = n(r); this.g = n(g); this.b = n(b);
}
defineIndexes(SFColor.prototype, ['r', 'g', 'b']);
method(SFColor.prototype, 'setHSV', function (h, s, v) {
  h = n(h); s = n(s); v = n(v);
  if (s <= 0) { this.r = this.g = this.b = v; return; }
  h = ((h % 360) + 360) % 360 / 60;
  var i = Math.floor(h), f = h - i;
  var p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
  var rgb = [[v, t, p], [q, v, p], [p, v, t], [p, q, v], [t, p, v], [v, p, q]][i % 6];
  this.r = rgb[0]; this.g = rgb[1]; this.b = rgb[2];
});
method(SFColor.prototype, 'getHSV', function () {
  var r = this.r, g = this.g, b = this.b;
  var max = Math.max(r, g, b), min = Math.min(r, g, b), d = max - min, h = 0;
  if (d > 0) {
    if (max === r) h = 60 * (((g - b) / d) % 6);
    else if (max === g) h = 60 * ((b - r) / d + 2);
    else h = 60 * ((r - g) / d + 4);
    if (h < 0) h += 360;
  }
  return [h, max > 0 ? d / max : 0, max];
});
method(SFColor.prototype, 'toString', function () { return fmt(this.r) + ' ' + fmt(this.g) + ' ' + fmt(this.b); });

// ---- SFRotation (axis x y z, angle in radians) ----
function quat(r) {  // [x, y, z, w] of a rotation, unit length
  var l = Math.sqrt(r.x * r.x + r.y * r.y + r.z * r.z);
  if (!(l > 0)) return [0, 0, 0, 1];
  var s = Math.sin(r.angle / 2) / l;
  return [r.x * s, r.y * s, r.z * s, Math.cos(r.angle / 2)];
}
function fromQuat(q) {
  var l = Math.sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  if (!(l > 0)) return new SFRotation(0, 0, 1, 0);
  var w = Math.max(-1, Math.min(1, q[3] / l));
  var s = Math.sqrt(1 - w * w);
  if (s < 1e-12) return new SFRotation(0, 0, 1, 0);
  return new SFRotation(q[0] / l / s, q[1] / l / s, q[2] / l / s, 2 * Math.acos(w));
}
function SFRotation(a, b, c, d) {
  if (!(this instanceof SFRotation)) return new SFRotation(a, b, c, d);
  if (a instanceof SFVec3f && b instanceof SFVec3f) {  // the rotation taking a to b
    var from = a.normalize(), to = b.normalize();
    var axis = from.cross(to), cos = Math.max(-1, Math.min(1, from.dot(to)));
    if (axis.length() < 1e-12) {
      if (cos > 0) { this.x = 0; this.y = 0; this.z = 1; this.angle = 0; return; }
      axis = Math.abs(from.x) < 0.9 ? from.cross(new SFVec3f(1, 0, 0)) : from.cross(new SFVec3f(0, 1, 0));
    }
    axis = axis.normalize();
    this.x = axis.x; this.y = axis.y; this.z = axis.z; this.angle = Math.acos(cos);
  } else if (a instanceof SFVec3f) {  // axis and angle
    this.x = a.x; this.y = a.y; this.z = a.z; this.angle = n(b);
  } else if (arguments.length === 0) {
    this.x = 0; this.y = 0; this.z = 1; this.angle = 0;
  } else {
    this.x = n(a); this.y = n(b); this.z = n(c); this.angle = n(d);
  }
}
defineIndexes(SFRotation.prototype, ['x', 'y', 'z', 'angle']);
method(SFRotation.prototype, 'getAxis', function () { return new SFVec3f(this.x, this.y, this.z); });
method(SFRotation.prototype, 'setAxis', function (v) { this.x = n(v.x); this.y = n(v.y); this.z = n(v.z); });
method(SFRotation.prototype, 'inverse', function () { return new SFRotation(this.x, this.y, this.z, -this.angle); });
// this * r as quaternions: the result applies r first, then this.
method(SFRotation.prototype, 'multiply', function (r) {
  var a = quat(this), b = quat(r);
  return fromQuat([a[3] * b[0] + a[0] * b[3] + a[1] * b[2] - a[2] * b[1],
                   a[3] * b[1] - a[0] * b[2] + a[1] * b[3] + a[2] * b[0],
                   a[3] * b[2] + a[0] * b[1] - a[1] * b[0] + a[2] * b[3],
                   a[3] * b[3] - a[0] * b[0] - a[1] * b[1] - a[2] * b[2]]);
});
method(SFRotation.prototype, 'multVec', function (v) {  // Rodrigues
  var l = Math.sqrt(this.x * this.x + this.y * this.y + this.z * this.z);
  if (!(l > 0)) return new SFVec3f(v.x, v.y, v.z);
  var k = new SFVec3f(this.x / l, this.y / l, this.z / l), c = Math.cos(this.angle), s = Math.sin(this.angle);
  var u = new SFVec3f(v.x, v.y, v.z);
  return u.multiply(c).add(k.cross(u).multiply(s)).add(k.multiply(k.dot(u) * (1 - c)));
});
method(SFRotation.prototype, 'slerp', function (dest, t) {
  var a = quat(this), b = quat(dest);
  var cos = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
  if (cos < 0) { b = [-b[0], -b[1], -b[2], -b[3]]; cos = -cos; }
  var k0 = 1 - t, k1 = t;
  if (cos < 0.9999) {
    var om = Math.acos(cos), so = Math.sin(om);
    k0 = Math.sin((1 - t) * om) / so; k1 = Math.sin(t * om) / so;
  }
  return fromQuat([a[0] * k0 + b[0] * k1, a[1] * k0 + b[1] * k1, a[2] * k0 + b[2] * k1, a[3] * k0 + b[3] * k1]);
});
method(SFRotation.prototype, 'toString', function () {
  return fmt(this.x) + ' ' + fmt(this.y) + ' ' + fmt(this.z) + ' ' + fmt(this.angle);
});

// ---- MF classes: Arrays with an MF prototype ----
// `blank` makes an element's default: the value a grown array (v.length = n) is filled
// with where the array is a node's field (__gsLiveMF).
function mfClass(name, convert, blank) {
  var ctor = function () {
    var a = [];
    for (var i = 0; i < arguments.length; ++i) a.push(convert(arguments[i]));
    Object.setPrototypeOf(a, ctor.prototype);
    return a;
  };
  ctor.prototype = Object.create(Array.prototype);
  method(ctor.prototype, 'constructor', ctor);
  method(ctor.prototype, 'toString', function () {
    var parts = [];
    for (var i = 0; i < this.length; ++i) parts.push(String(this[i]));
    return '[' + parts.join(', ') + ']';
  });
  method(ctor.prototype, '__blank', blank);
  G[name] = ctor;
  return ctor;
}
// A node's MF field as a Script holds it (script_live_fields.cpp): growing it, by its
// length or by an index past its end, fills the new elements with the type's default
// (X_ITE's arrays do; a bare Array would leave holes that v[i].setHSV cannot use).
// Duktape gives a trap an index as a number or a string; a length that is no array
// length, or past 2^24 elements, is left to the array itself (which throws a RangeError, or
// holds holes the Script's limits then bound).
var liveMFHandler = {
  set: function (t, k, v) {
    var end = 0;
    if (k === 'length') end = typeof v === 'number' && v === (v >>> 0) ? v : 0;
    else if (typeof k === 'number') end = k === (k >>> 0) ? k : 0;
    else if (typeof k === 'string' && String(k >>> 0) === k) end = k >>> 0;
    if (end <= 16777216)
      for (var i = t.length; i < end; ++i) t[i] = t.__blank();
    t[k] = v;
    return true;
  }
};
G.__gsLiveMF = function (a) { return new Proxy(a, liveMFHandler); };
function copyOf(C, v) {
  if (v instanceof C) { var c = Object.create(C.prototype); for (var k in v) c[k] = v[k]; return c; }
  if (v && typeof v === 'object' && !(v instanceof SFNode)) {
    return C.apply(null, [v[0], v[1], v[2], v[3]].slice(0, C.length));
  }
  return v;
}
mfClass('MFFloat', function (v) { return +v; }, function () { return 0; });
mfClass('MFTime', function (v) { return +v; }, function () { return 0; });
mfClass('MFInt32', function (v) { return v | 0; }, function () { return 0; });
mfClass('MFString', function (v) { return String(v); }, function () { return ''; });
mfClass('MFNode', function (v) { return v; }, function () { return null; });
mfClass('MFVec2f', function (v) { return copyOf(SFVec2f, v); }, function () { return new SFVec2f(); });
mfClass('MFVec3f', function (v) { return copyOf(SFVec3f, v); }, function () { return new SFVec3f(); });
mfClass('MFColor', function (v) { return copyOf(SFColor, v); }, function () { return new SFColor(); });
mfClass('MFRotation', function (v) { return copyOf(SFRotation, v); }, function () { return new SFRotation(); });

// ---- SFImage ----
function SFImage(x, y, comp, array) {
  if (!(this instanceof SFImage)) return new SFImage(x, y, comp, array);
  this.x = n(x) | 0; this.y = n(y) | 0; this.comp = n(comp) | 0;
  var a = G.MFInt32();
  if (array) for (var i = 0; i < array.length; ++i) a.push(array[i] | 0);
  this.array = a;
}
method(SFImage.prototype, 'toString', function () {
  return this.x + ' ' + this.y + ' ' + this.comp + (this.array.length ? ' ' + Array.prototype.join.call(this.array, ' ') : '');
});

// ---- SFNode: made by the host; new SFNode('VRML text') parses text ----
var makeNode = G.__gsNodeFromString, nodeName = G.__gsNodeName;
function SFNode(v) {
  if (v instanceof SFNode) return v;
  return makeNode(String(v));
}
method(SFNode.prototype, 'toString', function () { return nodeName(this); });
delete G.__gsNodeFromString;
delete G.__gsNodeName;

// ---- VrmlMatrix (C.6.17): 4x4, row-major, row vectors, translation in row 3 ----
function VrmlMatrix() {
  if (!(this instanceof VrmlMatrix)) return VrmlMatrix.apply(Object.create(VrmlMatrix.prototype), arguments);
  var a = arguments.length === 16 ? arguments : [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1];
  for (var i = 0; i < 4; ++i) this[i] = [n(a[4 * i]), n(a[4 * i + 1]), n(a[4 * i + 2]), n(a[4 * i + 3])];
  return this;
}
function mul(a, b) {  // a * b
  var r = new VrmlMatrix();
  for (var i = 0; i < 4; ++i)
    for (var j = 0; j < 4; ++j)
      r[i][j] = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j] + a[i][3] * b[3][j];
  return r;
}
function translation(t) { var m = new VrmlMatrix(); if (t) { m[3][0] = n(t.x); m[3][1] = n(t.y); m[3][2] = n(t.z); } return m; }
function scaling(s) { var m = new VrmlMatrix(); if (s) { m[0][0] = n(s.x); m[1][1] = n(s.y); m[2][2] = n(s.z); } return m; }
function rotation(r) {  // row-vector form: v * R rotates v by r
  var m = new VrmlMatrix();
  if (!r) return m;
  var e = [r.multVec(new SFVec3f(1, 0, 0)), r.multVec(new SFVec3f(0, 1, 0)), r.multVec(new SFVec3f(0, 0, 1))];
  for (var i = 0; i < 3; ++i) { m[i][0] = e[i].x; m[i][1] = e[i].y; m[i][2] = e[i].z; }
  return m;
}
method(VrmlMatrix.prototype, 'setTransform', function (t, r, s, so, c) {
  var neg = function (v) { return v ? new SFVec3f(-v.x, -v.y, -v.z) : v; };
  // v' = v * -C * -SR * S * SR * R * C * T (the Transform node's order for row vectors)
  var m = translation(neg(c));
  if (so) m = mul(m, rotation(so.inverse()));
  m = mul(m, scaling(s));
  if (so) m = mul(m, rotation(so));
  m = mul(m, rotation(r));
  m = mul(m, translation(c));
  m = mul(m, translation(t));
  for (var i = 0; i < 4; ++i) this[i] = m[i];
});
method(VrmlMatrix.prototype, 'getTransform', function (t, r, s) {
  if (t) { t.x = this[3][0]; t.y = this[3][1]; t.z = this[3][2]; }
  var rows = [0, 1, 2].map(function (i) { return new SFVec3f(this[i][0], this[i][1], this[i][2]); }, this);
  var sc = rows.map(function (v) { return v.length(); });
  if (s) { s.x = sc[0]; s.y = sc[1]; s.z = sc[2]; }
  if (r) {
    var m = rows.map(function (v, i) { return sc[i] > 0 ? v.divide(sc[i]) : v; });
    // rotation matrix (row-vector form) to quaternion
    var tr = m[0].x + m[1].y + m[2].z, q;
    if (tr > 0) {
      var S = Math.sqrt(tr + 1) * 2;
      q = [(m[1].z - m[2].y) / S, (m[2].x - m[0].z) / S, (m[0].y - m[1].x) / S, 0.25 * S];
    } else if (m[0].x > m[1].y && m[0].x > m[2].z) {
      var S1 = Math.sqrt(1 + m[0].x - m[1].y - m[2].z) * 2;
      q = [0.25 * S1, (m[1].x + m[0].y) / S1, (m[2].x + m[0].z) / S1, (m[1].z - m[2].y) / S1];
    } else if (m[1].y > m[2].z) {
      var S2 = Math.sqrt(1 + m[1].y - m[0].x - m[2].z) * 2;
      q = [(m[1].x + m[0].y) / S2, 0.25 * S2, (m[2].y + m[1].z) / S2, (m[2].x - m[0].z) / S2];
    } else {
      var S3 = Math.sqrt(1 + m[2].z - m[0].x - m[1].y) * 2;
      q = [(m[2].x + m[0].z) / S3, (m[2].y + m[1].z) / S3, 0.25 * S3, (m[0].y - m[1].x) / S3];
    }
    var rr = fromQuat(q);
    r.x = rr.x; r.y = rr.y; r.z = rr.z; r.angle = rr.angle;
  }
});
method(VrmlMatrix.prototype, 'transpose', function () {
  var r = new VrmlMatrix();
  for (var i = 0; i < 4; ++i) for (var j = 0; j < 4; ++j) r[i][j] = this[j][i];
  return r;
});
method(VrmlMatrix.prototype, 'inverse', function () {  // Gauss-Jordan
  var a = [0, 1, 2, 3].map(function (i) { return this[i].slice(); }, this), r = new VrmlMatrix();
  for (var c = 0; c < 4; ++c) {
    var p = c;
    for (var k = c + 1; k < 4; ++k) if (Math.abs(a[k][c]) > Math.abs(a[p][c])) p = k;
    if (Math.abs(a[p][c]) < 1e-300) return new VrmlMatrix();
    var t = a[c]; a[c] = a[p]; a[p] = t; t = r[c]; r[c] = r[p]; r[p] = t;
    var d = a[c][c];
    for (var j = 0; j < 4; ++j) { a[c][j] /= d; r[c][j] /= d; }
    for (var i = 0; i < 4; ++i) {
      if (i === c) continue;
      var f = a[i][c];
      for (var j2 = 0; j2 < 4; ++j2) { a[i][j2] -= f * a[c][j2]; r[i][j2] -= f * r[c][j2]; }
    }
  }
  return r;
});
method(VrmlMatrix.prototype, 'multLeft', function (m) { return mul(m, this); });
method(VrmlMatrix.prototype, 'multRight', function (m) { return mul(this, m); });
method(VrmlMatrix.prototype, 'multVecMatrix', function (v) {  // v * M
  var w = v.x * this[0][3] + v.y * this[1][3] + v.z * this[2][3] + this[3][3];
  w = w || 1;
  return new SFVec3f((v.x * this[0][0] + v.y * this[1][0] + v.z * this[2][0] + this[3][0]) / w,
                     (v.x * this[0][1] + v.y * this[1][1] + v.z * this[2][1] + this[3][1]) / w,
                     (v.x * this[0][2] + v.y * this[1][2] + v.z * this[2][2] + this[3][2]) / w);
});
method(VrmlMatrix.prototype, 'multMatrixVec', function (v) {  // M * v (column vector)
  var w = this[3][0] * v.x + this[3][1] * v.y + this[3][2] * v.z + this[3][3];
  w = w || 1;
  return new SFVec3f((this[0][0] * v.x + this[0][1] * v.y + this[0][2] * v.z + this[0][3]) / w,
                     (this[1][0] * v.x + this[1][1] * v.y + this[1][2] * v.z + this[1][3]) / w,
                     (this[2][0] * v.x + this[2][1] * v.y + this[2][2] * v.z + this[2][3]) / w);
});
method(VrmlMatrix.prototype, 'toString', function () {
  return [0, 1, 2, 3].map(function (i) { return this[i].join(' '); }, this).join(', ');
});

G.SFVec2f = SFVec2f; G.SFVec3f = SFVec3f; G.SFColor = SFColor; G.SFRotation = SFRotation;
G.SFImage = SFImage; G.SFNode = SFNode; G.VrmlMatrix = VrmlMatrix;
G.TRUE = true; G.FALSE = false;
// For the X3D classes (script_prelude_x3d.cpp), which take it and delete it.
G.__gsKit = { n: n, method: method, defineIndexes: defineIndexes, mfClass: mfClass, copyOf: copyOf,
              SFColor: SFColor, VrmlMatrix: VrmlMatrix };
})(this);
)JS";

}  // namespace gs::runtime::es
