"""omni.behavior"""
