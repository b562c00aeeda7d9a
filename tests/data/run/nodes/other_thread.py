import threading
import time


def main():
    threading.Thread(target=time.sleep, args=(1.0,)).start()
