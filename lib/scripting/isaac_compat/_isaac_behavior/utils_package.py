"""isaacsim.replicator.behavior.utils"""
