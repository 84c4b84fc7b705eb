"""usdrt: Fabric's view of the stage; in sdgbehave there is one stage, so
usdrt.Usd.Stage.Attach returns the same stage pxr sees."""
import types as _types

from _isaac_compat import module_getattr as _module_getattr
from pxr import Sdf as _Sdf

__getattr__ = _module_getattr(__name__)


class _RtStage:
    @staticmethod
    def Attach(stage_id):
        from pxr import UsdUtils
        return UsdUtils._stage_of(stage_id)


Usd = _types.SimpleNamespace(Stage=_RtStage)
Sdf = _types.SimpleNamespace(Path=_Sdf.Path)
