"""omni.ext: the extension base class (sdgbehave loads no extensions)."""


class IExt:
    def on_startup(self, ext_id):
        pass

    def on_shutdown(self):
        pass
