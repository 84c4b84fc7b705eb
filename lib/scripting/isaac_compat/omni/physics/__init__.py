"""omni.physics"""
