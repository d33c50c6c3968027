// The X3D ECMAScript classes (ISO/IEC 19777-1) beside annex C's, written in ECMAScript 5
// and run in each Script heap right after kPrelude (whose helpers it takes from
// __gsKit). The host (script_x3d.cpp) builds and reads these objects directly: SFVec2d
// {x,y}, SFVec3d {x,y,z}, SFVec4f/SFVec4d {x,y,z,w}, SFColorRGBA {r,g,b,a}, SFMatrix3f/3d
// {0..8} and SFMatrix4f/4d {0..15} (row by row, as X3D writes them: row vectors,
// translation in the last row, as VrmlMatrix); the MF classes are Arrays whose prototype
// is MFxxx.prototype. SFDouble is a plain number. Also X3DConstants, X3DFieldDefinition,
// SFNode.getFieldDefinitions / getNodeName, X3DRoute and the X3DScene object that
// Browser.currentScene returns (over the natives of __gsX3D, script_x3d.cpp).
#include "script_ecmascript_internal.hpp"

namespace gs::runtime::es {

const char* const kPreludeX3D = R"JS((function (G) {
'use strict';
var K = G.__gsKit, hooks = G.__gsX3D;
delete G.__gsKit;
delete G.__gsX3D;
var n = K.n, method = K.method, defineIndexes = K.defineIndexes, mfClass = K.mfClass, copyOf = K.copyOf;
var SFColor = K.SFColor, VrmlMatrix = K.VrmlMatrix, SFNode = G.SFNode;
function getter(proto, name, fn) {
  Object.defineProperty(proto, name, { get: fn, enumerable: false, configurable: true });
}

// ---- vectors and SFColorRGBA: components named by `keys` ----
function vecClass(keys, math) {
  var N = keys.length;
  function C(a, b, c, d) {
    var o = this instanceof C ? this : Object.create(C.prototype), args = [a, b, c, d];
    for (var i = 0; i < N; ++i) o[keys[i]] = n(args[i]);
    return o;
  }
  defineIndexes(C.prototype, keys);
  function make(f) {
    var o = Object.create(C.prototype);
    for (var i = 0; i < N; ++i) o[keys[i]] = f(keys[i]);
    return o;
  }
  if (math) {
    method(C.prototype, 'add', function (v) { var t = this; return make(function (k) { return t[k] + n(v[k]); }); });
    method(C.prototype, 'subtract', function (v) { var t = this; return make(function (k) { return t[k] - n(v[k]); }); });
    method(C.prototype, 'multiply', function (s) { var t = this; s = n(s); return make(function (k) { return t[k] * s; }); });
    method(C.prototype, 'divide', function (s) { var t = this; s = n(s); return make(function (k) { return t[k] / s; }); });
    method(C.prototype, 'negate', function () { var t = this; return make(function (k) { return -t[k]; }); });
    method(C.prototype, 'dot', function (v) {
      var d = 0;
      for (var i = 0; i < N; ++i) d += this[keys[i]] * n(v[keys[i]]);
      return d;
    });
    method(C.prototype, 'length', function () { return Math.sqrt(this.dot(this)); });
    method(C.prototype, 'normalize', function () {
      var l = this.length(), t = this;
      return make(function (k) { return l > 0 ? t[k] / l : 0; });
    });
    if (N === 3) {
      method(C.prototype, 'cross', function (v) {
        return new C(this.y * v.z - this.z * v.y, this.z * v.x - this.x * v.z, this.x * v.y - this.y * v.x);
      });
    }
  }
  method(C.prototype, 'toString', function () {
    var parts = [];
    for (var i = 0; i < N; ++i) parts.push(String(this[keys[i]]));
    return parts.join(' ');
  });
  return C;
}
var SFVec2d = vecClass(['x', 'y'], true), SFVec3d = vecClass(['x', 'y', 'z'], true);
var SFVec4f = vecClass(['x', 'y', 'z', 'w'], true), SFVec4d = vecClass(['x', 'y', 'z', 'w'], true);
var SFColorRGBA = vecClass(['r', 'g', 'b', 'a'], false);
// X3D's hue is in radians [0, 2 pi), as X_ITE takes and gives it (VRML97's prelude: degrees).
var degreesSetHSV = SFColor.prototype.setHSV, degreesGetHSV = SFColor.prototype.getHSV;
method(SFColor.prototype, 'setHSV', function (h, s, v) {
  degreesSetHSV.call(this, n(h) * 180 / Math.PI, s, v);
});
method(SFColor.prototype, 'getHSV', function () {
  var hsv = degreesGetHSV.call(this);
  hsv[0] = hsv[0] * Math.PI / 180;
  return hsv;
});
method(SFColorRGBA.prototype, 'setHSV', function (h, s, v) {
  var c = new SFColor();
  c.setHSV(h, s, v);
  this.r = c.r; this.g = c.g; this.b = c.b;
});
method(SFColorRGBA.prototype, 'getHSV', function () { return new SFColor(this.r, this.g, this.b).getHSV(); });

// ---- matrices: N x N numbers 0..N*N-1, row by row ----
function matClass(N, Vec) {
  var S = N * N, keys = N === 4 ? ['x', 'y', 'z'] : ['x', 'y'];
  function C() {
    var o = this instanceof C ? this : Object.create(C.prototype), a = arguments;
    for (var i = 0; i < S; ++i) o[i] = a.length === S ? n(a[i]) : (i % (N + 1) === 0 ? 1 : 0);
    return o;
  }
  function from(f) {
    var m = Object.create(C.prototype);
    for (var i = 0; i < S; ++i) m[i] = f(Math.floor(i / N), i % N);
    return m;
  }
  function mul(a, b) {  // a * b
    return from(function (r, c) {
      var s = 0;
      for (var k = 0; k < N; ++k) s += n(a[r * N + k]) * n(b[k * N + c]);
      return s;
    });
  }
  // v (N-1 components, then `last`) times the matrix as a row (rowVector) or column vector.
  function apply(m, v, last, rowVector, divide) {
    var u = [];
    for (var i = 0; i < N - 1; ++i) u.push(n(v[keys[i]]));
    u.push(last);
    var out = [];
    for (var j = 0; j < N; ++j) {
      var s = 0;
      for (var k = 0; k < N; ++k) s += u[k] * (rowVector ? m[k * N + j] : m[j * N + k]);
      out.push(s);
    }
    var w = divide ? (out[N - 1] || 1) : 1;
    return new Vec(out[0] / w, out[1] / w, N === 4 ? out[2] / w : 0);
  }
  method(C.prototype, 'transpose', function () { var t = this; return from(function (r, c) { return t[c * N + r]; }); });
  method(C.prototype, 'multLeft', function (m) { return mul(m, this); });
  method(C.prototype, 'multRight', function (m) { return mul(this, m); });
  method(C.prototype, 'multVecMatrix', function (v) { return apply(this, v, 1, true, true); });
  method(C.prototype, 'multMatrixVec', function (v) { return apply(this, v, 1, false, true); });
  method(C.prototype, 'multDirMatrix', function (v) { return apply(this, v, 0, true, false); });
  method(C.prototype, 'multMatrixDir', function (v) { return apply(this, v, 0, false, false); });
  method(C.prototype, 'inverse', function () {  // Gauss-Jordan; a singular matrix gives identity
    var a = [], r = [], i, j, c;
    for (i = 0; i < N; ++i) {
      a.push([]); r.push([]);
      for (j = 0; j < N; ++j) { a[i].push(n(this[i * N + j])); r[i].push(i === j ? 1 : 0); }
    }
    for (c = 0; c < N; ++c) {
      var p = c;
      for (i = c + 1; i < N; ++i) if (Math.abs(a[i][c]) > Math.abs(a[p][c])) p = i;
      if (Math.abs(a[p][c]) < 1e-300) return new C();
      var t = a[c]; a[c] = a[p]; a[p] = t; t = r[c]; r[c] = r[p]; r[p] = t;
      var d = a[c][c];
      for (j = 0; j < N; ++j) { a[c][j] /= d; r[c][j] /= d; }
      for (i = 0; i < N; ++i) {
        if (i === c) continue;
        var f = a[i][c];
        for (j = 0; j < N; ++j) { a[i][j] -= f * a[c][j]; r[i][j] -= f * r[c][j]; }
      }
    }
    return from(function (row, col) { return r[row][col]; });
  });
  method(C.prototype, 'toString', function () {
    var parts = [];
    for (var i = 0; i < S; ++i) parts.push(String(this[i]));
    return parts.join(' ');
  });
  if (N === 4) {
    // As VrmlMatrix: v' = v * -C * -SR * S * SR * R * C * T.
    method(C.prototype, 'setTransform', function (t, r, s, so, c) {
      var v = new VrmlMatrix();
      v.setTransform(t, r, s, so, c);
      for (var i = 0; i < S; ++i) this[i] = v[Math.floor(i / 4)][i % 4];
    });
    method(C.prototype, 'getTransform', function (t, r, s) {
      var a = [];
      for (var i = 0; i < S; ++i) a.push(this[i]);
      VrmlMatrix.apply(null, a).getTransform(t, r, s);
    });
  } else {
    // 2D: setTransform(translation, rotation angle, scale, scaleOrientation angle, center).
    var rot = function (angle) {
      var cs = Math.cos(n(angle)), sn = Math.sin(n(angle));
      return new C(cs, sn, 0, -sn, cs, 0, 0, 0, 1);
    };
    var move = function (v, sign) { return v ? new C(1, 0, 0, 0, 1, 0, sign * n(v.x), sign * n(v.y), 1) : new C(); };
    method(C.prototype, 'setTransform', function (t, r, s, so, c) {
      var m = mul(move(c, -1), rot(-n(so)));
      m = mul(m, s ? new C(n(s.x), 0, 0, 0, n(s.y), 0, 0, 0, 1) : new C());
      m = mul(mul(mul(mul(m, rot(so)), rot(r)), move(c, 1)), move(t, 1));
      for (var i = 0; i < S; ++i) this[i] = m[i];
    });
    // Fills translation and scale; returns the rotation angle.
    method(C.prototype, 'getTransform', function (t, r, s) {
      if (t) { t.x = this[6]; t.y = this[7]; }
      if (s) { s.x = Math.sqrt(this[0] * this[0] + this[1] * this[1]); s.y = Math.sqrt(this[3] * this[3] + this[4] * this[4]); }
      return Math.atan2(this[1], this[0]);
    });
  }
  return C;
}
var SFMatrix3f = matClass(3, G.SFVec2f), SFMatrix3d = matClass(3, SFVec2d);
var SFMatrix4f = matClass(4, G.SFVec3f), SFMatrix4d = matClass(4, SFVec3d);

function copyMatrix(C, S, v) {
  if (v instanceof C) { var c = Object.create(C.prototype); for (var i = 0; i < S; ++i) c[i] = v[i]; return c; }
  if (v && typeof v === 'object') {
    var a = [];
    for (var j = 0; j < S; ++j) a.push(v[j]);
    return C.apply(null, a);
  }
  return v;
}

mfClass('MFBool', function (v) { return !!v; }, function () { return false; });
mfClass('MFDouble', function (v) { return +v; }, function () { return 0; });
mfClass('MFImage', function (v) { return v; }, function () { return new SFImage(0, 0, 0); });
mfClass('MFVec2d', function (v) { return copyOf(SFVec2d, v); }, function () { return new SFVec2d(); });
mfClass('MFVec3d', function (v) { return copyOf(SFVec3d, v); }, function () { return new SFVec3d(); });
mfClass('MFVec4f', function (v) { return copyOf(SFVec4f, v); }, function () { return new SFVec4f(); });
mfClass('MFVec4d', function (v) { return copyOf(SFVec4d, v); }, function () { return new SFVec4d(); });
mfClass('MFColorRGBA', function (v) { return copyOf(SFColorRGBA, v); }, function () { return new SFColorRGBA(); });
mfClass('MFMatrix3f', function (v) { return copyMatrix(SFMatrix3f, 9, v); }, function () { return new SFMatrix3f(); });
mfClass('MFMatrix3d', function (v) { return copyMatrix(SFMatrix3d, 9, v); }, function () { return new SFMatrix3d(); });
mfClass('MFMatrix4f', function (v) { return copyMatrix(SFMatrix4f, 16, v); }, function () { return new SFMatrix4f(); });
mfClass('MFMatrix4d', function (v) { return copyMatrix(SFMatrix4d, 16, v); }, function () { return new SFMatrix4d(); });

// ---- X3DConstants: access types and field types (19777-1's numbering) ----
var X3DConstants = {
  initializeOnly: 0, inputOnly: 1, outputOnly: 2, inputOutput: 3,
  NOT_STARTED_STATE: 0, IN_PROGRESS_STATE: 1, COMPLETE_STATE: 2, FAILED_STATE: 3,
  // Browser events (19777-1 7.2, the browser listeners; the numbers are this browser's)
  CONNECTION_ERROR: 0, BROWSER_EVENT: 1, INITIALIZED_EVENT: 2, SHUTDOWN_EVENT: 3, INITIALIZED_ERROR: 4
};
var types = ['Bool', 'Color', 'ColorRGBA', 'Double', 'Float', 'Image', 'Int32', 'Matrix3d', 'Matrix3f',
             'Matrix4d', 'Matrix4f', 'Node', 'Rotation', 'String', 'Time', 'Vec2d', 'Vec2f', 'Vec3d',
             'Vec3f', 'Vec4d', 'Vec4f'];
types.forEach(function (t, i) { X3DConstants['SF' + t] = i; X3DConstants['MF' + t] = types.length + i; });
// Node types (19777-1 clause 7.9.1): every concrete and abstract type of the node model.
var nodeTypes = hooks.nodeTypeConstants();
for (var k = 0; k < nodeTypes.length; k += 2) X3DConstants[nodeTypes[k]] = nodeTypes[k + 1];
Object.freeze(X3DConstants);

function X3DFieldDefinition(name, accessType, dataType) {
  Object.defineProperty(this, 'name', { value: name, enumerable: true });
  Object.defineProperty(this, 'accessType', { value: accessType, enumerable: true });
  Object.defineProperty(this, 'dataType', { value: dataType, enumerable: true });
}
method(SFNode.prototype, 'getFieldDefinitions', function () {
  var defs = hooks.fieldDefinitions(this), out = [];
  for (var i = 0; i < defs.length; ++i)
    out.push(new X3DFieldDefinition(defs[i][0], defs[i][1], X3DConstants[defs[i][2]]));
  return out;
});
method(SFNode.prototype, 'getNodeName', function () { return hooks.typeName(this); });
method(SFNode.prototype, 'getNodeType', function () { return hooks.nodeType(this); });

// ---- X3DRoute and X3DScene (Browser.currentScene) ----
function X3DRoute(a, af, b, bf) {
  Object.defineProperty(this, 'sourceNode', { value: a, enumerable: true });
  Object.defineProperty(this, 'sourceField', { value: af, enumerable: true });
  Object.defineProperty(this, 'destinationNode', { value: b, enumerable: true });
  Object.defineProperty(this, 'destinationField', { value: bf, enumerable: true });
}
function X3DExecutionContext() { throw new TypeError('X3DExecutionContext cannot be made by a Script'); }
function X3DScene() { throw new TypeError('X3DScene cannot be made by a Script'); }
X3DScene.prototype = Object.create(X3DExecutionContext.prototype);
var P = X3DScene.prototype;
method(P, 'constructor', X3DScene);
// Each hook takes the scene object first: Browser.currentScene (the world) or one that
// Browser.createX3DFromString made (the host knows it by a hidden id).
getter(P, 'specificationVersion', function () { return hooks.sceneInfo(this)[0]; });
getter(P, 'encoding', function () { return hooks.sceneInfo(this)[1]; });
getter(P, 'worldURL', function () { return hooks.sceneInfo(this)[2]; });
getter(P, 'rootNodes', function () { return hooks.rootNodes(this); });
method(P, 'getNamedNode', function (name) {
  var node = hooks.namedNode(this, String(name));
  if (node === null) throw new Error("getNamedNode: the scene has no node named '" + name + "'");
  return node;
});
// Named nodes (X3DExecutionContext, 19777-1 7.4.11; as X_ITE 15): namedNodes lists the
// scene's DEF names and those Scripts gave; add throws on a name in use, update gives a
// node the name (its DEF name), remove takes a name away.
getter(P, 'namedNodes', function () { return hooks.namedNodes(this); });
method(P, 'addNamedNode', function (name, node) { hooks.editNamedNode(this, 0, String(name), node); });
method(P, 'updateNamedNode', function (name, node) { hooks.editNamedNode(this, 1, String(name), node); });
method(P, 'removeNamedNode', function (name) { hooks.editNamedNode(this, 2, String(name), null); });
method(P, 'createNode', function (typeName) { return hooks.createNode(String(typeName)); });
method(P, 'addRoute', function (a, af, b, bf) {
  af = String(af); bf = String(bf);
  if (!hooks.route(this, true, a, af, b, bf))
    throw new Error('addRoute: cannot route ' + af + ' to ' + bf);
  return new X3DRoute(a, af, b, bf);
});
method(P, 'deleteRoute', function (a, af, b, bf) {
  if (a instanceof X3DRoute) return hooks.route(this, false, a.sourceNode, a.sourceField, a.destinationNode, a.destinationField);
  return hooks.route(this, false, a, String(af), b, String(bf));
});
// routes (19777-1 7.4.11): the scene's ROUTEs still in place, its file's and those its
// addRoute made, in that order.
getter(P, 'routes', function () {
  var all = hooks.routes(this), out = [];
  for (var i = 0; i < all.length; ++i) out.push(new X3DRoute(all[i][0], all[i][1], all[i][2], all[i][3]));
  return out;
});
// META statements (X3DScene, as X_ITE 15): getMetaData(name) gives the values of `name`
// (an Array of strings) or undefined; setMetaData replaces them (a value or an Array of
// them), addMetaData adds one, removeMetaData removes the name.
method(P, 'getMetaData', function (name) { return hooks.metaData(this, 0, String(name), null); });
method(P, 'setMetaData', function (name, values) {
  if (!Array.isArray(values)) values = [values];
  hooks.metaData(this, 1, String(name), values.map(String));
});
method(P, 'addMetaData', function (name, value) { hooks.metaData(this, 2, String(name), [String(value)]); });
method(P, 'removeMetaData', function (name) { hooks.metaData(this, 3, String(name), null); });
// X3DProtoDeclaration / X3DExternProtoDeclaration (19777-1 7.4.12, 7.4.13): read-only
// views of the scene's declarations, newInstance() through the scene's createProto.
function X3DProtoDeclaration(d, scene) {
  var fields = [];
  for (var i = 0; i < d[3].length; ++i)
    fields.push(new X3DFieldDefinition(d[3][i][0], d[3][i][1], X3DConstants[d[3][i][2]]));
  Object.defineProperty(this, 'name', { value: d[0], enumerable: true });
  Object.defineProperty(this, 'fields', { value: fields, enumerable: true });
  Object.defineProperty(this, 'isExternProto', { value: d[1], enumerable: true });
  Object.defineProperty(this, '__gsScene', { value: scene });
  if (d[1]) {
    var urls = new MFString();
    for (var u = 0; u < d[2].length; ++u) urls[u] = d[2][u];
    Object.defineProperty(this, 'urls', { value: urls, enumerable: true });
  }
}
method(X3DProtoDeclaration.prototype, 'newInstance', function () { return hooks.createProto(this.__gsScene, this.name); });
function declarations(scene, external) {
  var all = hooks.protoDeclarations(scene), out = [];
  for (var i = 0; i < all.length; ++i)
    if (all[i][1] === external) out.push(new X3DProtoDeclaration(all[i], scene));
  return out;
}
getter(P, 'protos', function () { return declarations(this, false); });
getter(P, 'externprotos', function () { return declarations(this, true); });
method(P, 'createProto', function (name) { return hooks.createProto(this, String(name)); });
method(P, 'addRootNode', function (node) { hooks.rootNode(this, true, node); });
method(P, 'removeRootNode', function (node) { hooks.rootNode(this, false, node); });
method(P, 'getImportedNode', function (name) {
  var node = hooks.importedNode(this, String(name));
  if (node === null)
    throw new Error("getImportedNode: no IMPORT '" + name + "' whose Inline has arrived and EXPORTs it");
  return node;
});
// X3DScene.getExportedNode (19777-1): the node the scene EXPORTs as `name`.
method(P, 'getExportedNode', function (name) {
  var node = hooks.exportedNode(this, String(name));
  if (node === null) throw new Error("getExportedNode: the scene EXPORTs no node as '" + name + "'");
  return node;
});
// addExportedNode throws on a name in use (create3000's Core/EXPORT.x3d counts on it),
// updateExportedNode sets it, removeExportedNode takes it away (X3DScene, as X_ITE 15).
method(P, 'addExportedNode', function (name, node) { hooks.editExportedNode(this, 0, String(name), node); });
method(P, 'updateExportedNode', function (name, node) { hooks.editExportedNode(this, 1, String(name), node); });
method(P, 'removeExportedNode', function (name) { hooks.editExportedNode(this, 2, String(name), null); });

// ---- ComponentInfo, ProfileInfo, UnitInfo (19777-1 7.3: read-only objects) ----
// The natives (script_x3d_info.cpp) give [name, level, title], [name, title, [component
// ...]] and [category, name, conversionFactor]; the arrays made of them are frozen.
function readOnly(o, props) {
  for (var k in props) Object.defineProperty(o, k, { value: props[k], enumerable: true });
  return o;
}
function ComponentInfo() { throw new TypeError('ComponentInfo cannot be made by a Script'); }
function ProfileInfo() { throw new TypeError('ProfileInfo cannot be made by a Script'); }
function UnitInfo() { throw new TypeError('UnitInfo cannot be made by a Script'); }
// A profile reads as its name (X3DScene.profile was the name before it was an object).
method(ProfileInfo.prototype, 'toString', function () { return this.name; });
function componentInfo(d) {
  return readOnly(Object.create(ComponentInfo.prototype), { name: d[0], level: d[1], title: d[2], providerURL: '' });
}
function componentInfos(all) { return Object.freeze(all.map(componentInfo)); }
function profileInfo(d) {
  if (d === null) return null;
  return readOnly(Object.create(ProfileInfo.prototype),
                  { name: d[0], level: 0, title: d[1], providerURL: '', components: componentInfos(d[2]) });
}
getter(P, 'profile', function () { return profileInfo(hooks.sceneProfile(this)); });
getter(P, 'components', function () { return componentInfos(hooks.sceneComponents(this)); });
// Edits of the scene's COMPONENT and UNIT statements (as X_ITE 15 names them): the
// statements only; what was read keeps its units.
method(P, 'hasComponent', function (name, level) {
  name = String(name); level = level === undefined ? 0 : Number(level);
  return this.components.some(function (c) { return c.name === name && c.level >= level; });
});
method(P, 'addComponent', function (component) { hooks.editComponent(this, 0, String(component.name), component.level); });
method(P, 'updateComponent', function (component) { hooks.editComponent(this, 1, String(component.name), component.level); });
method(P, 'removeComponent', function (name) { hooks.editComponent(this, 2, String(name), 0); });
method(P, 'updateUnit', function (category, name, factor) { hooks.editUnit(this, String(category), String(name), Number(factor)); });
method(P, 'getUnit', function (category) {
  category = String(category);
  return this.units.filter(function (u) { return u.category === category; })[0] || null;
});
getter(P, 'units', function () {
  return Object.freeze(hooks.sceneUnits(this).map(function (u) {
    return readOnly(Object.create(UnitInfo.prototype), { category: u[0], name: u[1], conversionFactor: u[2] });
  }));
});

// toVRMLString, toXMLString, toJSONString (X_ITE 15's names; 19777-1 has the node's first
// two): the scene's whole file, or the node alone, in X3D's Classic VRML, XML or JSON
// encoding, as `ghostspace convert` writes them.
['toVRMLString', 'toXMLString', 'toJSONString'].forEach(function (name, encoding) {
  method(P, name, function () { return hooks.sceneText(this, encoding); });
  method(SFNode.prototype, name, function () { return hooks.nodeText(this, encoding); });
});

// ---- Browser's X3D additions (19777-1 7.2), put on Browser by installBrowser ----
// Browser callbacks: X_ITE 15's addBrowserCallback(key, [event,] callback) and 19777-1's
// addBrowserListener(listener); each is called with the event's number (X3DConstants
// INITIALIZED_EVENT once the world's load ran every initialize(), INITIALIZED_ERROR when
// its file ended short or a link it asked for could not open, SHUTDOWN_EVENT before
// shutdown() when the world is unloaded).
var callbacks = [];  // [key, event or -1 for every event, function]
function removeCallbacks(key, event) {
  callbacks = callbacks.filter(function (c) { return !(c[0] === key && (event === undefined || c[1] === event)); });
}
// Each callback runs even when one before it threw; the first error is then thrown.
Object.defineProperty(G, '__gsBrowserEvent', { value: function (event) {
  var now = callbacks.slice(), failed = null;
  for (var i = 0; i < now.length; ++i) {
    if (now[i][1] !== -1 && now[i][1] !== event) continue;
    try { now[i][2].call(null, event); } catch (e) { if (failed === null) failed = e; }
  }
  if (failed !== null) throw failed;
} });
G.__gsBrowserX3D = function (B) {
  getter(B, 'supportedProfiles', function () { return Object.freeze(hooks.profiles().map(profileInfo)); });
  getter(B, 'supportedComponents', function () { return componentInfos(hooks.components()); });
  method(B, 'getProfile', function (name) {
    var p = hooks.profile(String(name));
    if (p === null) throw new Error("getProfile: profile '" + name + "' is not supported");
    return profileInfo(p);
  });
  method(B, 'getComponent', function (name, level) {
    var c = hooks.component(String(name), level);
    if (c === null) throw new Error("getComponent: component '" + name + "' is not supported");
    return componentInfo(c);
  });
  method(B, 'getRenderingProperty', function (name) { return hooks.renderingProperty(String(name)); });
  method(B, 'addBrowserCallback', function (key, event, fn) {
    if (arguments.length < 3) { fn = event; event = -1; } else { event = Number(event); }
    if (typeof fn !== 'function') throw new TypeError('addBrowserCallback: the callback is no function');
    removeCallbacks(key, event === -1 ? undefined : event);
    callbacks.push([key, event, fn]);
  });
  method(B, 'removeBrowserCallback', function (key, event) {
    removeCallbacks(key, event === undefined ? undefined : Number(event));
  });
  method(B, 'addBrowserListener', function (fn) {
    if (typeof fn !== 'function') throw new TypeError('addBrowserListener: the listener is no function');
    removeCallbacks(fn);
    callbacks.push([fn, -1, fn]);
  });
  method(B, 'removeBrowserListener', function (fn) { removeCallbacks(fn); });
};
G.ComponentInfo = ComponentInfo; G.ProfileInfo = ProfileInfo; G.UnitInfo = UnitInfo;

G.SFVec2d = SFVec2d; G.SFVec3d = SFVec3d; G.SFVec4f = SFVec4f; G.SFVec4d = SFVec4d;
G.SFColorRGBA = SFColorRGBA; G.SFMatrix3f = SFMatrix3f; G.SFMatrix3d = SFMatrix3d;
G.SFMatrix4f = SFMatrix4f; G.SFMatrix4d = SFMatrix4d; G.X3DConstants = X3DConstants;
G.X3DFieldDefinition = X3DFieldDefinition; G.X3DRoute = X3DRoute;
G.X3DProtoDeclaration = X3DProtoDeclaration;
G.X3DExecutionContext = X3DExecutionContext; G.X3DScene = X3DScene;
G.__gsScene = Object.create(P);  // Browser.currentScene (installBrowser takes it)
// Makes the X3DScene object of createX3DFromString (installBrowser keeps it in the stash).
var create = Object.create;  // as the prelude found it: a Script may replace Object.create
G.__gsSceneMaker = function () { return create(P); };
})(this);
)JS";

}  // namespace gs::runtime::es
