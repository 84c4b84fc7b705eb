"""omni.kit"""
