"""omni.replicator"""
