"""rclpy.service and rclpy.client, simulated: servers nobody outside the node calls.

A bras-kit run has one node process and no ``ros2 service call``: a server waits (its callback
never runs) and the node goes on, as on Jazzy when nobody calls it. A client sees the servers
of the nodes of the same run (rclpy 7.1.6 client.py:163-190 service_is_ready/wait_for_service).
"""

import _bras_sim

from .qos import QoSProfile


def check_is_valid_srv_type(srv_type):
    """rclpy/type_support.py check_is_valid_srv_type: a service class has Request and Response."""
    from .exceptions import NoTypeSupportImportedException

    if not (hasattr(srv_type, 'Request') and hasattr(srv_type, 'Response')):
        raise NoTypeSupportImportedException()


class Service:
    """rclpy 7.1.6 service.py:30-62."""

    def __init__(self, srv_type, srv_name, callback, callback_group, qos_profile):
        self.srv_type = srv_type
        self.srv_name = srv_name
        self.callback = callback
        self.callback_group = callback_group
        self.qos_profile = qos_profile
        self._destroyed = False

    @property
    def service_name(self):
        return self.srv_name

    def destroy(self):
        self._destroyed = True


def servers_on(name):
    return [service for node in _bras_sim.STATE.nodes if not node._destroyed
            for service in node._services_list if service.srv_name == name and not service._destroyed]


class Client:
    """rclpy 7.1.6 client.py."""

    def __init__(self, node, srv_type, srv_name, qos_profile, callback_group):
        self._node = node
        self.srv_type = srv_type
        self.srv_name = srv_name
        self.qos_profile = qos_profile
        self.callback_group = callback_group
        self._destroyed = False

    @property
    def service_name(self):
        return self.srv_name

    def service_is_ready(self):
        return bool(servers_on(self.srv_name))

    def wait_for_service(self, timeout_sec=None):
        """client.py:172-190: polls every 0.25 s while the context is ok."""
        sleep_time = 0.25
        if timeout_sec is None:
            timeout_sec = float('inf')
        while self._node.context.ok() and not self.service_is_ready() and timeout_sec > 0.0:
            _bras_sim.sleep(sleep_time)
            timeout_sec -= sleep_time
        return self.service_is_ready()

    def call_async(self, request):
        """A server of the same run answers at once (on Jazzy, when both nodes' executors
        spin); with none, the future stays pending, as it does on Jazzy."""
        from .task import Future

        if not isinstance(request, self.srv_type.Request):
            raise TypeError(f'Expected {self.srv_type.Request}, got {type(request)}')
        future = Future()
        servers = servers_on(self.srv_name)
        if servers:
            future.set_result(servers[0].callback(request, self.srv_type.Response()))
        return future

    def destroy(self):
        self._destroyed = True


def qos_services_default():
    return QoSProfile(depth=10)
