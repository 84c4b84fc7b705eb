# Fails at a known line inside a task, after an update.
import asyncio

import omni.kit.app


async def main():
    await omni.kit.app.get_app().next_update_async()
    raise RuntimeError("the program's own error")


asyncio.ensure_future(main())
