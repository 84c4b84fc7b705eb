"""isaacsim.replicator"""
