"""isaacsim.core"""
