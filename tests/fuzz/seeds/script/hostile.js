function initialize() { var a = []; for (var i = 0; i < 100; i++) a.push(new MFFloat(1, 2, 3)); s = new MFString(String.fromCharCode(0)); }
function tick(t) { while (true) {} }
function fraction(v) { var o = {}; o.self = o; Browser.addRoute(node, 'translation_changed', node, 'set_translation'); }
