// The ECMAScript Script host (ISO/IEC 14772-1:1997 clause 4.12 and annex C) on Duktape:
// one Duktape heap per Script node, each call run under ScriptLimits (a time budget and
// a memory cap). What is supported and the sandbox's rules: docs/runtime-scripts.md.
#pragma once

#include "runtime/script_host.hpp"

namespace gs::runtime {

/// The factory for ExecutionOptions::scripts: runs `javascript:`, `ecmascript:` and
/// `vrmlscript:` url entries inline, and other entries read with
/// ScriptContext::fetchText. Null (with diagnostics) when no entry of the url can run.
ScriptFactory ecmascriptFactory();

}  // namespace gs::runtime
