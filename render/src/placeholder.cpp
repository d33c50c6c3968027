// Placeholder so the module has a source; delete once render/ has real sources.
