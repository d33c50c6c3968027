function initialize() { f = 0.5; v = new SFVec3f(1, 2, 3); s = new MFString('a', 'b'); n = node; }
function tick(t, ts) { var x = ints[1] + t; print('tick ' + x); Browser.setDescription('d' + x); }
function fraction(v2, ts) { v = new SFVec3f(v2, v2 * 2, 0); node.set_translation = v; f = v2; var r = new SFRotation(0, 1, 0, v2); var c = new SFColor(v2, 0, 1); }
function eventsProcessed() { n = Browser.createVrmlFromString('Group {}')[0]; }
