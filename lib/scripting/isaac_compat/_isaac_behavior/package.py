"""isaacsim.replicator.behavior as sdgbehave provides it: the constants and
helpers Isaac's behavior scripts and driver programs import, and
`behaviors`, whose classes stand for sdgbehave's built-in behaviors. A copy
of Isaac's own extension in a folder above a script replaces this package
(docs/isaac-scripts.md)."""
